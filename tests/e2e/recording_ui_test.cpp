// Recording and replay in the window (issue 6 items 2-3), offscreen: the File menu entry, a
// simulator session recorded with its console lines, commands, ground truth and its samples as
// the frames a robot would have sent (decoded, they are the live samples; the recording replays),
// a recording without received bytes refused for replay, and robot bytes from a recording
// replayed through a LinkedRobot into the session as a live link would deliver them.

#include "app/gui/recording_ui.hpp"

#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QFile>
#include <QMenu>
#include <QMenuBar>
#include <QSettings>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>
#include <algorithm>
#include <chrono>
#include <memory>

#include "app/gui/app_options.hpp"
#include "app/gui/drive_input_controller.hpp"
#include "app/gui/link_controller.hpp"
#include "app/gui/link_ui.hpp"
#include "app/gui/main_window.hpp"
#include "app/recording/recording_reader.hpp"
#include "app/recording/replay_player.hpp"
#include "app/recording/rerun_engine.hpp"
#include "app/recording/session_recorder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "tests/e2e/app_test_support.hpp"
#include "tests/e2e/main_window_fixture.hpp"

namespace irgs::gui {
namespace {

namespace mav = comms::mavlink;

class RecordingUiTest : public test::MainWindowFixture {
 protected:
  void SetUp() override {
    openWindow(test::squareRoom());
    recording_ = new RecordingUi(*session_, window_->linkUi().controller(), *window_);
  }
  void TearDown() override {
    window_.reset();  // and with it the RecordingUi
    session_.reset();
  }
  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds / 0.02 + 0.5); ++i)
      session_->tick(0.02);
  }
  QString path(const char* name) const { return dir_.filePath(QString::fromLatin1(name)); }

  RecordingUi* recording_ = nullptr;
};

TEST_F(RecordingUiTest, TheFileMenuOffersOpenRecording) {
  QMenu* file = nullptr;
  for (QAction* top : window_->menuBar()->actions()) {
    if (top->menu() != nullptr && top->menu()->title() == QStringLiteral("&File"))
      file = top->menu();
  }
  ASSERT_NE(file, nullptr);
  EXPECT_TRUE(file->actions().contains(recording_->openRecordingAction()));
}

TEST_F(RecordingUiTest, RecordsConsoleLinesCommandsAndSimulatorTruth) {
  ASSERT_EQ(recording_->startRecording(path("sim.irgsrec")), QString());
  session_->drive(0.2, 0.0);
  run(1.0);
  session_->stopRobot();
  run(0.2);
  session_->report(EventLevel::kWarning, QStringLiteral("a warning for the timeline"));
  recording_->stopRecording();

  const recording::LoadResult loaded = recording::loadRecording(path("sim.irgsrec").toStdString());
  ASSERT_TRUE(loaded.recording) << loaded.error;
  const recording::Recording& r = *loaded.recording;
  EXPECT_GE(r.truth.size(), 40u);  // one per GUI tick
  EXPECT_GT(r.truth.back().x_m, 0.1);
  ASSERT_EQ(r.commands.size(), 2u);
  EXPECT_EQ(r.commands[0].text, "drive 0.200 0.000");
  EXPECT_EQ(r.commands[1].text, "stop");
  EXPECT_TRUE(std::any_of(r.events.begin(), r.events.end(), [](const auto& e) {
    return e.kind == "warning" && e.text == "a warning for the timeline";
  }));
  EXPECT_GT(r.receivedFrameCount(), 0u);  // the samples, as a robot's frames
  EXPECT_EQ(r.meta.at("robot"), session_->profile().name);

  EXPECT_FALSE(recording_->openReplay(path("missing.irgsrec")).isEmpty());
}

TEST_F(RecordingUiTest, ASimulatorSessionIsRecordedAsTheFramesItsSamplesWouldBe) {
  std::vector<TelemetrySample> live;
  QObject::connect(session_.get(), &SessionController::sampleIntegrated,
                   [&live](const TelemetrySample& sample) { live.push_back(sample); });
  ASSERT_EQ(recording_->startRecording(path("sim.irgsrec")), QString());
  session_->drive(0.25, 0.4);  // an arc, so x, y and heading all change
  run(3.0);
  session_->stopRobot();
  run(0.5);
  recording_->stopRecording();
  ASSERT_GE(live.size(), 100u);

  const recording::LoadResult loaded = recording::loadRecording(path("sim.irgsrec").toStdString());
  ASSERT_TRUE(loaded.recording) << loaded.error;
  EXPECT_EQ(loaded.recording->meta.count("telemetry_source"), 1u);
  const recording::DecodedRecording decoded =
      recording::decodeRecording(*loaded.recording, session_->profile());
  EXPECT_EQ(decoded.stats.decoder.bad_crc, 0u);
  // Every live sample comes back, in order, as the link would deliver it: the pose in float
  // (a few micrometres at these distances), the heading likewise, sonar ranges in millimetres.
  ASSERT_EQ(decoded.samples.size(), live.size());
  std::size_t sonar_readings = 0;
  for (std::size_t i = 0; i < live.size(); ++i) {
    const TelemetrySample& want = live[i];
    const TelemetrySample& got = decoded.samples[i].sample;
    EXPECT_NEAR(got.time_s, want.time_s, 1e-3) << i;
    EXPECT_NEAR(got.odometry_pose.x, want.odometry_pose.x, 1e-5) << i;
    EXPECT_NEAR(got.odometry_pose.y, want.odometry_pose.y, 1e-5) << i;
    EXPECT_NEAR(got.odometry_pose.theta, want.odometry_pose.theta, 1e-5) << i;
    ASSERT_EQ(got.sonar.size(), want.sonar.size()) << i;
    for (std::size_t k = 0; k < want.sonar.size(); ++k) {
      EXPECT_EQ(got.sonar[k].sensor, want.sonar[k].sensor);
      EXPECT_EQ(got.sonar[k].echo, want.sonar[k].echo);
      if (got.sonar[k].echo && want.sonar[k].echo) {
        EXPECT_NEAR(got.sonar[k].range_m, want.sonar[k].range_m, 0.00051);
      }
    }
    sonar_readings += want.sonar.size();
  }
  EXPECT_GT(sonar_readings, 0u);

  // Re-run with the recorded parameters: the map the session built live, to rounding (the pose
  // crossed the "link" in float, the ranges in millimetres).
  const recording::RerunParameters recorded =
      recording::recordedRerunParameters(loaded.recording->meta);
  const recording::RerunResult rerun = recording::rerunRecording(
      *loaded.recording, session_->profile(), WorldMap{}, recorded, recorded);
  ASSERT_EQ(rerun.error, "");
  const GridComparison live_map = compareGrids(session_->grid(), rerun.recorded.grid);
  EXPECT_GT(live_map.compared_cells, 1000u);
  EXPECT_GT(live_map.agreement, 0.99);
  EXPECT_GT(live_map.occupied_tolerant.f1, 0.98);

  // And it replays as a link: the replayed robot ends where the simulated one did.
  ASSERT_EQ(recording_->openReplay(path("sim.irgsrec"), 16.0), QString());
  ASSERT_TRUE(recording_->replaying());
  EXPECT_EQ(session_->simulationControl(), nullptr);
  QSignalSpy drained(recording_, &RecordingUi::replayDrained);
  session_->start();
  ASSERT_TRUE(drained.wait(20000)) << "the replay never drained";
  ASSERT_TRUE(session_->latestSample());
  EXPECT_NEAR(session_->latestSample()->odometry_pose.x, live.back().odometry_pose.x, 1e-5);
  EXPECT_NEAR(session_->latestSample()->odometry_pose.y, live.back().odometry_pose.y, 1e-5);
}

TEST_F(RecordingUiTest, AReplayDoesNotForceTheWindowTallerThanALaptopScreen) {
  // A 1366 x 768 screen less the task bar and the title bar leaves about 700 px. Replaying adds
  // the replay bar, the link-health panel and, on the Drive tab, the robot behaviours: the tab
  // scrolls instead of setting the window's minimum height (it was 1090 px).
  ASSERT_EQ(recording_->startRecording(path("short.irgsrec")), QString());
  session_->drive(0.2, 0.0);
  run(1.0);
  recording_->stopRecording();
  DriveInputController pad(window_->commandPanel(), *session_, std::make_unique<test::NoGamepad>());
  ASSERT_EQ(recording_->openReplay(path("short.irgsrec")), QString());
  ASSERT_TRUE(recording_->bar().isVisibleTo(window_.get()));
  QTabWidget& tabs = window_->controlTabs();
  ASSERT_GE(tabs.count(), 3);
  for (int tab = 0; tab < tabs.count(); ++tab) {
    tabs.setCurrentIndex(tab);
    QApplication::processEvents();
    const QSize minimum = window_->minimumSizeHint().expandedTo(window_->minimumSize());
    EXPECT_LE(minimum.height(), 700) << tabs.tabText(tab).toStdString();
    EXPECT_LE(minimum.width(), 1366) << tabs.tabText(tab).toStdString();
  }
}

TEST_F(RecordingUiTest, ARecordingWithoutReceivedBytesIsRefusedForReplay) {
  {
    auto opened = recording::SessionRecorder::create(path("truth.irgsrec").toStdString(), {});
    ASSERT_TRUE(opened.recorder) << opened.error;
    opened.recorder->recordTruth(0.0, 0.0, 0.0);
    opened.recorder->recordTruth(0.1, 0.0, 0.0);
  }
  const QString refused = recording_->openReplay(path("truth.irgsrec"));
  EXPECT_TRUE(refused.contains(QStringLiteral("no received link bytes"))) << refused.toStdString();
  EXPECT_FALSE(recording_->replaying());
  EXPECT_NE(session_->simulationControl(), nullptr);
}

TEST_F(RecordingUiTest, ReplaysRecordedRobotBytesThroughALinkedRobotIntoTheSession) {
  // A robot's stream: heartbeats and 40 poses at 20 Hz moving along +x, recorded as received.
  constexpr int kPoses = 40;
  constexpr float kStep_m = 0.0625f;
  {
    auto opened = recording::SessionRecorder::create(path("robot.irgsrec").toStdString(), {});
    ASSERT_TRUE(opened.recorder) << opened.error;
    mav::FrameEncoder encoder(1, 1);
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < kPoses; ++i) {
      const auto t = t0 + std::chrono::milliseconds(50 * i);
      if (i % 20 == 0) {
        mav::Heartbeat hb;
        hb.type = static_cast<std::uint8_t>(mav::MavType::kGroundRover);
        const auto frame = encoder.encode(hb);
        opened.recorder->recordFrame(comms::TapDirection::kReceived, t, frame.view());
      }
      mav::IrgsPose2d pose;
      pose.time_boot_ms = static_cast<std::uint32_t>(1000 + 50 * i);
      pose.x = kStep_m * static_cast<float>(i);
      const auto frame = encoder.encode(pose);
      opened.recorder->recordFrame(comms::TapDirection::kReceived, t, frame.view());
    }
  }
  recording_->setCollectTrajectory(true);
  ASSERT_EQ(recording_->openReplay(path("robot.irgsrec"), 16.0), QString());
  ASSERT_TRUE(recording_->replaying());
  EXPECT_EQ(recording_->player()->speed(), 16.0);
  EXPECT_TRUE(window_->linkUi().controller().linked());  // a linked robot, as live
  EXPECT_EQ(session_->simulationControl(), nullptr);
  QSignalSpy drained(recording_, &RecordingUi::replayDrained);
  session_->start();
  ASSERT_TRUE(drained.wait(20000)) << "the replay never drained";
  ASSERT_TRUE(session_->latestSample());
  EXPECT_NEAR(session_->latestSample()->odometry_pose.x, kStep_m * (kPoses - 1), 1e-6);
  ASSERT_GE(recording_->trajectory().size(), 2u);
  for (std::size_t i = 1; i < recording_->trajectory().size(); ++i)
    EXPECT_GE(recording_->trajectory()[i].pose.x, recording_->trajectory()[i - 1].pose.x);

  // The Reset action rebuilds the replayed robot: it has seen nothing, so the replay restarts.
  session_->resetRobotToStart();
  ASSERT_TRUE(recording_->replaying());
  EXPECT_EQ(recording_->player()->position_s(), 0.0);
  EXPECT_EQ(recording_->player()->chunksFed(), 0u);

  recording_->closeReplay();
  EXPECT_FALSE(recording_->replaying());
  EXPECT_NE(session_->simulationControl(), nullptr);  // back to the simulator
  EXPECT_FALSE(window_->linkUi().controller().linked());

  // Another robot taking over ends the replay and keeps that robot.
  ASSERT_EQ(recording_->openReplay(path("robot.irgsrec"), 16.0), QString());
  session_->setRobotFactory(test::simulatedFactory(3));
  EXPECT_FALSE(recording_->replaying());
  EXPECT_NE(session_->simulationControl(), nullptr);
}

AppOptionsResult parse(const QStringList& arguments) {
  return parseAppOptions(QStringList{QStringLiteral("irgs")} + arguments);
}

TEST(RecordingOptions, ParseRecordReplayAndDumpFiles) {
  const AppOptionsResult record =
      parse({QStringLiteral("--record"), QStringLiteral("a.irgsrec"), QStringLiteral("--grid-out"),
             QStringLiteral("g.csv"), QStringLiteral("--trajectory-out"), QStringLiteral("t.csv")});
  ASSERT_TRUE(record.options) << record.message.toStdString();
  EXPECT_EQ(record.options->record_file, QStringLiteral("a.irgsrec"));
  EXPECT_EQ(record.options->grid_out_file, QStringLiteral("g.csv"));
  EXPECT_EQ(record.options->trajectory_out_file, QStringLiteral("t.csv"));
  EXPECT_FALSE(record.options->no_record);
  const AppOptionsResult replay = parse({QStringLiteral("--replay"), QStringLiteral("a.irgsrec"),
                                         QStringLiteral("--replay-speed"), QStringLiteral("0.25")});
  ASSERT_TRUE(replay.options) << replay.message.toStdString();
  EXPECT_EQ(replay.options->replay_file, QStringLiteral("a.irgsrec"));
  EXPECT_EQ(replay.options->replay_speed, 0.25);
  EXPECT_TRUE(parse({QStringLiteral("--no-record")}).options->no_record);
}

TEST(RecordingOptions, RejectContradictionsAndSpeedsOutsideAQuarterToSixteen) {
  for (const QStringList& bad :
       {QStringList{QStringLiteral("--record"), QStringLiteral("a"), QStringLiteral("--no-record")},
        QStringList{QStringLiteral("--replay"), QStringLiteral("a"), QStringLiteral("--connect"),
                    QStringLiteral("tcp://127.0.0.1:5760")},
        QStringList{QStringLiteral("--replay-speed"), QStringLiteral("32")},
        QStringList{QStringLiteral("--replay-speed"), QStringLiteral("0.1")},
        QStringList{QStringLiteral("--replay"), QStringLiteral(" ")}}) {
    const AppOptionsResult result = parse(bad);
    EXPECT_FALSE(result.options) << bad.join(QLatin1Char(' ')).toStdString();
    EXPECT_EQ(result.exit_code, 2);
  }
}

TEST(RecordingPaths, NewFilesGoBesideACustomSettingsFileAndNeverReuseANameInUse) {
  QTemporaryDir dir;
  ASSERT_TRUE(dir.isValid());
  EXPECT_EQ(RecordingUi::defaultRecordingsDir(dir.filePath(QStringLiteral("s.ini"))),
            dir.filePath(QStringLiteral("recordings")));
  const QString first = RecordingUi::newRecordingPath(dir.path());
  EXPECT_TRUE(first.endsWith(QStringLiteral(".irgsrec")));
  QFile file(first);
  ASSERT_TRUE(file.open(QIODevice::WriteOnly));
  file.close();
  const QString second = RecordingUi::newRecordingPath(dir.path());
  EXPECT_NE(first, second);
}

}  // namespace
}  // namespace irgs::gui
