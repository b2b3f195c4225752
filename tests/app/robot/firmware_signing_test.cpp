// FirmwareCore with a MAVLink signing key (docs/protocol.md, "Who may drive"): only frames signed
// with the key are acted on; unsigned, wrongly signed and replayed ones move nothing and are
// counted and reported. On a fake clock, through receiveBytes() as irgs-robot feeds it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "app/robot/firmware_core.hpp"
#include "firmware_test_support.hpp"

namespace irgs::app::firmware_test {
namespace {

// Wall clock of the tests' "boot": any fixed signing time (2023).
constexpr std::uint64_t kBoot = 8ull * 365 * 86400 * mav::kSigningTicksPerSecond;

mav::SigningKey keyOf(std::uint8_t seed) {
  mav::SigningKey key{};
  for (std::size_t i = 0; i < key.size(); ++i)
    key[i] = static_cast<std::uint8_t>(seed + 7 * i);
  return key;
}

FirmwareConfig signedConfig() {
  FirmwareConfig config;
  config.signing_key = keyOf(1);
  config.signing_time_at_boot = kBoot;
  return config;
}

// A ground station that starts at firmware time `start_s`, signs with `key` (or not) on the
// firmware's clock plus `clock_offset_s`, and reads the firmware's frames verifying them with the
// firmware's key.
class Station {
 public:
  Station(FirmwareCore& core, std::optional<mav::SigningKey> key, double start_s = 0.0,
          double clock_offset_s = 0.0)
      : core_(core),
        clock_offset_s_(clock_offset_s),
        now_(start_s),
        next_hb_(start_s),
        next_mc_(start_s) {
    if (key)
      encoder_.enableSigning(*key, 0);
    if (core.config().signing_key)
      decoder_.setSigningKey(core.config().signing_key, /*require_signed=*/true);
  }

  template <class M>
  void send(const M& message, double t) {
    const auto ticks = static_cast<std::uint64_t>((t + clock_offset_s_) * 1e5);
    const mav::EncodedFrame frame = encoder_.encode(message, kBoot + ticks);
    sent_.insert(sent_.end(), frame.view().begin(), frame.view().end());
    ++frames_sent_;
    core_.receiveBytes(frame.view(), t);
  }
  // Feeds bytes recorded earlier, as an attacker replaying them would.
  void replay(const std::vector<std::uint8_t>& bytes, double t) { core_.receiveBytes(bytes, t); }

  // Heartbeats every 0.5 s and MANUAL_CONTROL x every 0.1 s (when given) from now_ to `until`.
  void run(double until, std::optional<std::int16_t> forward) {
    while (now_ + 1e-9 < until) {
      now_ += 0.01;
      if (now_ + 1e-9 >= next_hb_) {
        mav::Heartbeat hb;
        hb.type = static_cast<std::uint8_t>(mav::MavType::kGcs);
        send(hb, now_);
        next_hb_ = now_ + 0.5;
      }
      if (forward && now_ + 1e-9 >= next_mc_) {
        mav::ManualControl mc;
        mc.target = 1;
        mc.x = *forward;
        send(mc, now_);
        next_mc_ = now_ + 0.1;
      }
      idle(now_);
    }
  }
  void idle(double t) {
    core_.advance(t);
    std::vector<mav::Frame> frames;
    decoder_.feed(core_.takeOutput(), frames);
    received_.insert(received_.end(), frames.begin(), frames.end());
  }

  std::vector<std::string> statusTexts() const {
    std::vector<std::string> out;
    for (const mav::Frame& f : received_)
      if (auto s = f.as<mav::Statustext>())
        out.emplace_back(s->text.data(), strnlen(s->text.data(), s->text.size()));
    return out;
  }
  std::optional<mav::SysStatus> lastSysStatus() const {
    std::optional<mav::SysStatus> last;
    for (const mav::Frame& f : received_)
      if (auto s = f.as<mav::SysStatus>())
        last = *s;
    return last;
  }
  std::size_t receivedFrames() const { return received_.size(); }
  const mav::DecodeCounters& readerTotals() const { return decoder_.totals(); }
  const std::vector<std::uint8_t>& sent() const { return sent_; }
  std::uint64_t framesSent() const { return frames_sent_; }
  double now() const { return now_; }

 private:
  FirmwareCore& core_;
  double clock_offset_s_;
  mav::FrameEncoder encoder_{255, 190};
  mav::FrameDecoder decoder_;
  std::vector<mav::Frame> received_;
  std::vector<std::uint8_t> sent_;
  std::uint64_t frames_sent_ = 0;
  double now_;
  double next_hb_;
  double next_mc_;
};

double travelled(const FirmwareCore& core) {
  const Pose2 pose = core.simulator().truePose();
  return std::hypot(pose.x, pose.y);  // from the start at the origin
}

TEST(FirmwareSigning, UnsignedManualControlMovesNothingIsCountedAndReported) {
  FirmwareCore core = makeCore(room(false), signedConfig());
  Station intruder(core, std::nullopt);
  intruder.run(1.5, 600);
  EXPECT_EQ(travelled(core), 0.0);
  EXPECT_FALSE(core.safety().gcs_alive);  // its heartbeats do not count either
  const mav::DecodeCounters& rx = core.decodeTotals();
  EXPECT_EQ(rx.frames, 0u);
  EXPECT_EQ(rx.unsigned_rejected, intruder.framesSent());
  EXPECT_EQ(core.refusedFrames(), rx.unsigned_rejected);
  const auto status = intruder.lastSysStatus();
  ASSERT_TRUE(status);
  EXPECT_GT(status->errors_comm, 0u);
  EXPECT_EQ(status->drop_rate_comm, 10000u);  // every frame received was refused
  const auto texts = intruder.statusTexts();
  ASSERT_EQ(texts.size(), 1u);  // once, then at most every 5 s
  EXPECT_EQ(texts[0], "unsigned/bad signature: 1 refused (1 total)");
}

TEST(FirmwareSigning, AGroundStationWithTheKeyDrivesAndReadsSignedTelemetry) {
  FirmwareCore core = makeCore(room(false), signedConfig());
  Station station(core, keyOf(1));
  station.run(1.5, 600);
  EXPECT_GT(travelled(core), 0.1);
  EXPECT_EQ(core.refusedFrames(), 0u);
  // Everything the firmware sent verified with the key (the reader requires signatures).
  EXPECT_GT(station.receivedFrames(), 100u);
  EXPECT_EQ(station.readerTotals().unsigned_rejected, 0u);
  EXPECT_EQ(station.readerTotals().bad_signature, 0u);
}

TEST(FirmwareSigning, AWrongKeyAndAReplayMoveNothingAndAreCounted) {
  FirmwareCore core = makeCore(room(false), signedConfig());
  Station owner(core, keyOf(1));
  owner.run(1.0, 600);
  const double moved = travelled(core);
  ASSERT_GT(moved, 0.05);
  owner.run(2.0, std::nullopt);  // heartbeats only: teleop expires, the robot stops
  ASSERT_TRUE(stopped(core));
  const double at_rest = travelled(core);

  Station forger(core, keyOf(2), 2.0);
  forger.run(3.0, 600);
  EXPECT_GT(core.decodeTotals().bad_signature, 0u);
  // Replaying the owner's recorded frames (heartbeats and MANUAL_CONTROL) a second later.
  const std::uint64_t before = core.decodeTotals().replay_rejected;
  for (double t = 3.0; t < 4.0; t += 0.1) {  // ten times
    owner.replay(owner.sent(), t);
    owner.idle(t);
  }
  EXPECT_GT(core.decodeTotals().replay_rejected, before);
  EXPECT_EQ(travelled(core), at_rest);
  EXPECT_TRUE(stopped(core));
}

TEST(FirmwareSigning, AFreshRobotRefusesARecordingOlderThanAMinute) {
  FirmwareCore core = makeCore(room(false), signedConfig());
  // Frames signed two minutes before the robot's boot, by a station with the right key.
  Station recording(core, keyOf(1), 0.0, -120.0);
  recording.run(1.0, 600);
  EXPECT_EQ(travelled(core), 0.0);
  EXPECT_GT(core.decodeTotals().replay_rejected, 0u);
}

TEST(FirmwareSigning, WithoutAKeyTheFirmwareSendsUnsignedAndAcceptsEverything) {
  FirmwareCore core = makeCore(room(false));
  Station station(core, std::nullopt);
  station.run(1.0, 600);
  EXPECT_GT(travelled(core), 0.05);
  EXPECT_EQ(core.refusedFrames(), 0u);
}

}  // namespace
}  // namespace irgs::app::firmware_test
