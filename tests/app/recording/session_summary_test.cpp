// The session summary of a recording: distance from the decoded odometry (one pose type), link
// quality from a fresh decoder, events; Markdown and HTML output; the irgs-summary tool on a
// real recording file.

#include "app/recording/session_summary.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/recording/session_recorder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "tests/app/recording/recording_test_support.hpp"

namespace irgs::recording {
namespace {

namespace mav = comms::mavlink;

// 101 poses 1 cm apart along x (1.00 m), each sent as IRGS_POSE_2D and LOCAL_POSITION_NED (which
// must not count twice), one frame with a broken checksum, two sequence numbers skipped.
Recording robotRecording() {
  Recording r;
  r.meta["program"] = "irgs test";
  mav::FrameEncoder encoder(1, 1);
  for (int i = 0; i <= 100; ++i) {
    mav::IrgsPose2d pose;
    pose.time_boot_ms = static_cast<std::uint32_t>(i * 50);
    pose.x = static_cast<float>(0.01 * i);
    mav::LocalPositionNed ned;
    ned.x = pose.x;
    const mav::EncodedFrame a = encoder.encode(pose);
    const mav::EncodedFrame b = encoder.encode(ned);
    RecordedFrame frame{0.05 * i, 0, {}};
    frame.bytes.assign(a.view().begin(), a.view().end());
    frame.bytes.insert(frame.bytes.end(), b.view().begin(), b.view().end());
    if (i == 40)
      frame.bytes[12] ^= 0xFF;  // corrupt the pose's payload: CRC error, that pose is lost
    if (i == 70)
      encoder.encode(ned), encoder.encode(ned);  // two sequence numbers never sent
    r.frames.push_back(std::move(frame));
  }
  r.frames.push_back({5.1, 1, {0xFD, 0x00}});  // one sent frame
  r.events.push_back({1.0, "info", "Mode: linked robot"});
  r.events.push_back({2.0, "warning", "Link lost <serial>"});
  r.events.push_back({2.5, "link", "CRC errors: +1"});
  r.commands.push_back({0.5, "drive 0.2 0"});
  return r;
}

TEST(SessionSummary, DistanceLinkQualityAndEventsOfALinkedRecording) {
  const SessionSummary s = summarizeRecording(robotRecording(), "test.irgsrec");
  EXPECT_NEAR(s.duration_s, 5.1, 1e-9);
  EXPECT_NEAR(s.distance_m, 1.0, 1e-5);  // the corrupted pose's neighbours still join up
  EXPECT_EQ(s.distance_from, "odometry, IRGS_POSE_2D");
  ASSERT_TRUE(s.link.has_value());
  EXPECT_EQ(s.link->crc_errors, 1u);
  EXPECT_EQ(s.link->frames_received, 201u);
  EXPECT_EQ(s.link->frames_sent, 1u);
  // The two never sent and the corrupted one (to the receiver it is missing too).
  EXPECT_EQ(s.link->sequence_gaps, 3u);
  EXPECT_EQ(s.link->link_losses, 1u);
  EXPECT_EQ(s.link->messages.at("IRGS_POSE_2D"), 100u);
  EXPECT_EQ(s.commands, 1u);
  ASSERT_EQ(s.events.size(), 2u);  // the warning and the link event; info is counted only
  EXPECT_EQ(s.event_counts.at("info"), 1u);

  const std::string md = summaryMarkdown(s);
  EXPECT_NE(md.find("| Distance | 1.00 m (odometry, IRGS_POSE_2D) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| CRC errors | 1 |"), std::string::npos);
  EXPECT_NE(md.find("| 2.00 | warning | Link lost <serial> |"), std::string::npos);
  const std::string html = summaryHtml(s);
  EXPECT_NE(html.find("Link lost &lt;serial&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<serial>"), std::string::npos);
}

TEST(SessionSummary, ASimulatorRecordingMeasuresTheTruth) {
  Recording r;
  for (int i = 0; i <= 10; ++i)
    r.truth.push_back({0.1 * i, 0.0, 0.03 * i, 0.0});
  const SessionSummary s = summarizeRecording(r, "sim.irgsrec");
  EXPECT_FALSE(s.link.has_value());
  EXPECT_NEAR(s.distance_m, 0.3, 1e-12);
  EXPECT_EQ(s.distance_from, "simulator truth");
  EXPECT_NE(summaryMarkdown(s).find("No warnings, errors or link events."), std::string::npos);
}

TEST(SessionSummary, TheCommandLineToolWritesMarkdownAndHtmlFromARecordingFile) {
  testing::ensureCoreApplication();
  const auto dir = testing::makeTempDir("irgs-summary");
  const std::string rec = (dir / "run.irgsrec").string();
  {
    auto opened = SessionRecorder::create(rec, {{"program", "summary test"}});
    ASSERT_TRUE(opened.recorder) << opened.error;
    const Recording source = robotRecording();
    const auto t0 = std::chrono::steady_clock::now();
    for (const RecordedFrame& f : source.frames) {
      opened.recorder->recordFrame(
          static_cast<comms::TapDirection>(f.dir),
          t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                   std::chrono::duration<double>(f.t_s)),
          f.bytes);
    }
    opened.recorder->recordEvent("warning", "Link lost <serial>");
  }
  const std::string md = (dir / "summary.md").string();
  const std::string html = (dir / "summary.html").string();
  ASSERT_EQ(std::system((std::string(IRGS_SUMMARY_EXE) + " " + rec + " " + md).c_str()), 0);
  ASSERT_EQ(std::system((std::string(IRGS_SUMMARY_EXE) + " " + rec + " " + html).c_str()), 0);
  std::ifstream in(md);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("| Distance | 1.00 m (odometry, IRGS_POSE_2D) |"), std::string::npos)
      << text.str();
  EXPECT_NE(text.str().find("| CRC errors | 1 |"), std::string::npos);
  EXPECT_TRUE(std::filesystem::file_size(html) > 500);
  // Bad arguments and an unknown output type fail with a status.
  EXPECT_NE(std::system((std::string(IRGS_SUMMARY_EXE) + " " + rec + " " +
                         (dir / "x.txt").string() + " 2>/dev/null")
                            .c_str()),
            0);
  EXPECT_NE(std::system((std::string(IRGS_SUMMARY_EXE) + " 2>/dev/null").c_str()), 0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace irgs::recording
