// TelemetryFrameWriter: a simulator's samples, written as frames, decoded by the link path's
// FrameDecoder and TelemetryAssembler, come back as the same samples (within the messages'
// resolution). This is what makes a simulator recording replay like a robot's.

#include "comms/robot/telemetry_frame_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/messages.hpp"
#include "comms/robot/telemetry_assembler.hpp"
#include "core/sim/gyro_sim.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/sim/simulator.hpp"
#include "tests/comms/robot/robot_test_support.hpp"

namespace irgs::comms {
namespace {

namespace mav = mavlink;

// Drives the thesis robot around the default map for `seconds`, turning now and then, and
// returns every sample (100 Hz, sonar, gyro, IR proximity, bumpers when it touches a wall).
std::vector<TelemetrySample> simulatedSamples(double seconds, std::uint64_t seed,
                                              const RobotProfile& robot = testing::thesisRobot()) {
  SimConfig config;
  config.seed = seed;
  config = typicalSimConfig(config);
  config.gyro = autogyroErrorModel();  // an AUTOGYRO-level gyro, as the GUI's simulator has
  config.gyro.enabled = true;
  Simulator sim(testing::defaultMap(), robot, config);
  std::vector<TelemetrySample> samples;
  const int steps = static_cast<int>(std::lround(seconds / sim.config().dt_s));
  for (int i = 0; i < steps; ++i) {
    const bool turning = (i / 150) % 3 == 2;
    sim.setCommand({turning ? 0.05 : 0.3, turning ? 0.8 : 0.1});
    samples.push_back(sim.step());
  }
  return samples;
}

struct Decoded {
  std::vector<TelemetrySample> samples;
  mav::DecodeCounters decoder;
  std::uint64_t heartbeats = 0;
  std::size_t bytes = 0;
};

Decoded writeAndDecode(const std::vector<TelemetrySample>& samples,
                       const RobotProfile& robot = testing::thesisRobot()) {
  TelemetryFrameWriter writer(robot);
  TelemetryAssembler assembler(robot);
  mav::FrameDecoder decoder;
  Decoded out;
  std::vector<mav::Frame> frames;
  for (const TelemetrySample& s : samples) {
    const std::vector<std::uint8_t> bytes = writer.write(s);
    out.bytes += bytes.size();
    frames.clear();
    decoder.feed(bytes, frames);
    for (const mav::Frame& f : frames) {
      if (f.message_id == mav::Heartbeat::kId)
        ++out.heartbeats;
      assembler.onFrame(f, s.time_s);
    }
    for (TelemetrySample& r : assembler.takeReady())
      out.samples.push_back(std::move(r));
  }
  assembler.tick(samples.back().time_s + 1.0);  // the last one waits for its hold time
  for (TelemetrySample& r : assembler.takeReady())
    out.samples.push_back(std::move(r));
  out.decoder = decoder.totals();
  return out;
}

TEST(TelemetryFrameWriter, TheAssemblerGetsBackEverySampleWithinTheMessagesResolution) {
  const std::vector<TelemetrySample> live = simulatedSamples(20.0, 3);
  const Decoded decoded = writeAndDecode(live);
  EXPECT_EQ(decoded.decoder.bad_crc, 0u);
  EXPECT_EQ(decoded.decoder.sequence_gaps, 0u);
  EXPECT_EQ(decoded.heartbeats, 20u);  // once a second of robot time
  ASSERT_EQ(decoded.samples.size(), live.size());
  std::size_t readings = 0;
  std::size_t echoes = 0;
  std::size_t gyro = 0;
  for (std::size_t i = 0; i < live.size(); ++i) {
    const TelemetrySample& a = live[i];
    const TelemetrySample& b = decoded.samples[i];
    ASSERT_NEAR(b.time_s, a.time_s, 1e-9) << i;
    EXPECT_NEAR(b.odometry_pose.x, a.odometry_pose.x, 1e-6) << i;
    EXPECT_NEAR(b.odometry_pose.y, a.odometry_pose.y, 1e-6) << i;
    EXPECT_NEAR(wrapAngle(b.odometry_pose.theta - a.odometry_pose.theta), 0.0, 1e-6) << i;
    EXPECT_NEAR(b.measured_velocity.linear_mps, a.measured_velocity.linear_mps, 1e-6) << i;
    EXPECT_EQ(b.left_ticks, a.left_ticks) << i;
    EXPECT_EQ(b.right_ticks, a.right_ticks) << i;
    EXPECT_EQ(b.bumpers, a.bumpers) << i;
    ASSERT_EQ(b.proximity_m.size(), a.proximity_m.size()) << i;
    for (std::size_t k = 0; k < a.proximity_m.size(); ++k) {
      EXPECT_NEAR(b.proximity_m[k], a.proximity_m[k], 0.5e-3) << i << " IR " << k;
    }
    ASSERT_EQ(b.sonar.size(), a.sonar.size()) << i;
    for (std::size_t k = 0; k < a.sonar.size(); ++k) {
      EXPECT_EQ(b.sonar[k].sensor, a.sonar[k].sensor) << i;
      EXPECT_EQ(b.sonar[k].echo, a.sonar[k].echo) << i;
      if (a.sonar[k].echo) {
        EXPECT_NEAR(b.sonar[k].range_m, a.sonar[k].range_m, 0.5e-3) << i;
        ++echoes;
      }
      ++readings;
    }
    ASSERT_EQ(b.gyro.has_value(), a.gyro.has_value()) << i;
    if (a.gyro) {
      EXPECT_NEAR(b.gyro->rate_radps, a.gyro->rate_radps, 0.5e-3) << i;
      EXPECT_NEAR(b.gyro->temperature_c, a.gyro->temperature_c, 0.005) << i;
      ++gyro;
    }
    EXPECT_FALSE(b.true_pose.has_value());  // truth is recorded apart, never on the link
  }
  EXPECT_GT(readings, 500u);
  EXPECT_GT(echoes, 100u);
  EXPECT_EQ(gyro, live.size());
}

// The floor sensors of paper 004's robot and the six caster encoders of paper 000's, with the
// robot's own J+ residual: exact (counts are integers, the residual sum a double).
TEST(TelemetryFrameWriter, FloorSensorCountsAndCasterEncodersComeBackExactly) {
  const RobotProfile mouse_robot = testing::robotProfile("mouse_type20_004.json");
  const std::vector<TelemetrySample> mouse_live = simulatedSamples(5.0, 4, mouse_robot);
  const Decoded mouse = writeAndDecode(mouse_live, mouse_robot);
  ASSERT_EQ(mouse.samples.size(), mouse_live.size());
  for (std::size_t i = 0; i < mouse_live.size(); ++i) {
    const TelemetrySample& a = mouse_live[i];
    const TelemetrySample& b = mouse.samples[i];
    ASSERT_TRUE(a.mouse.has_value()) << i;
    ASSERT_TRUE(b.mouse.has_value()) << i;
    EXPECT_EQ(b.mouse->right.dx, a.mouse->right.dx) << i;
    EXPECT_EQ(b.mouse->right.dy, a.mouse->right.dy) << i;
    EXPECT_EQ(b.mouse->left.dx, a.mouse->left.dx) << i;
    EXPECT_EQ(b.mouse->left.dy, a.mouse->left.dy) << i;
    EXPECT_EQ(b.mouse->right.status, a.mouse->right.status) << i;
    EXPECT_EQ(b.mouse->left.status, a.mouse->left.status) << i;
  }
  EXPECT_NE(mouse_live.back().mouse->right.dx, 0);  // it moved

  const RobotProfile caster_robot = testing::robotProfile("caster3_000.json");
  const std::vector<TelemetrySample> caster_live = simulatedSamples(5.0, 4, caster_robot);
  const Decoded caster = writeAndDecode(caster_live, caster_robot);
  ASSERT_EQ(caster.samples.size(), caster_live.size());
  for (std::size_t i = 0; i < caster_live.size(); ++i) {
    ASSERT_TRUE(caster_live[i].casters.has_value()) << i;
    ASSERT_TRUE(caster.samples[i].casters.has_value()) << i;
    EXPECT_EQ(*caster.samples[i].casters, *caster_live[i].casters) << i;
  }
  EXPECT_GT(caster_live.back().casters->residual_periods, 0);
}

TEST(TelemetryFrameWriter, ASampleOlderThanTheLastStartsOverWithAHeartbeat) {
  TelemetryFrameWriter writer(testing::thesisRobot());
  TelemetrySample s;
  s.time_s = 5.0;
  mav::FrameDecoder decoder;
  std::vector<mav::Frame> frames;
  auto heartbeats = [&](const std::vector<std::uint8_t>& bytes) {
    frames.clear();
    decoder.feed(bytes, frames);
    int n = 0;
    for (const auto& f : frames)
      n += f.message_id == mav::Heartbeat::kId ? 1 : 0;
    return n;
  };
  EXPECT_EQ(heartbeats(writer.write(s)), 1);
  s.time_s = 5.5;
  EXPECT_EQ(heartbeats(writer.write(s)), 0);
  s.time_s = 0.0;  // a new robot
  EXPECT_EQ(heartbeats(writer.write(s)), 1);
}

}  // namespace
}  // namespace irgs::comms
