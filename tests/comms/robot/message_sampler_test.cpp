// MessageSampler: every numeric field of a robot frame reaches its sample by the generated
// table; thinning per stream (message id + instance) by arrival time; the robot clock from the
// messages' own time stamps, untimed messages at the newest one; a bounded queue.

#include "comms/robot/message_sampler.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string_view>

#include "comms/mavlink/frame_decoder.hpp"
#include "comms/mavlink/frame_encoder.hpp"
#include "comms/mavlink/messages.hpp"

namespace irgs::comms {
namespace {

namespace mav = mavlink;

template <class M>
mav::Frame frameOf(const M& message) {
  static mav::FrameEncoder encoder(1, 1);
  mav::FrameDecoder decoder;
  const auto result = decoder.feed(encoder.encode(message).view());
  if (result.frames.size() != 1)
    throw std::logic_error("frameOf: not one frame");
  return result.frames[0];
}

mav::IrgsPose2d pose(std::uint32_t time_ms, float x) {
  mav::IrgsPose2d p;
  p.time_boot_ms = time_ms;
  p.x = x;
  p.y = -0.5f;
  p.theta = 1.25f;
  p.v = 0.25f;
  p.omega = -0.125f;
  return p;
}

MessageSamplerConfig on(double rate_hz = 25.0) {
  MessageSamplerConfig c;
  c.max_rate_hz = rate_hz;
  return c;
}

TEST(MessageSampler, EveryNumericFieldOfAFrameIsInItsSampleInTableOrder) {
  MessageSampler sampler(on());
  sampler.onFrame(frameOf(pose(1500, 2.5f)), 0.0);
  const auto samples = sampler.take();
  ASSERT_EQ(samples.size(), 1u);
  const MessageSample& s = samples[0];
  ASSERT_NE(s.message, nullptr);
  EXPECT_EQ(s.message->name, "IRGS_POSE_2D");
  EXPECT_FALSE(s.instance.has_value());
  EXPECT_DOUBLE_EQ(s.robot_time_s, 1.5);
  ASSERT_EQ(s.values.size(), s.message->fields.size());
  const std::vector<double> expected{1500.0, 2.5, -0.5, 1.25, 0.25, -0.125};
  EXPECT_EQ(s.values, expected);
  EXPECT_TRUE(sampler.take().empty());
}

TEST(MessageSampler, OffSamplesNothing) {
  MessageSampler sampler;
  EXPECT_FALSE(sampler.enabled());
  sampler.onFrame(frameOf(pose(1000, 1.0f)), 0.0);
  EXPECT_TRUE(sampler.take().empty());
  EXPECT_THROW(MessageSampler(on(-1.0)), std::invalid_argument);
}

TEST(MessageSampler, AStreamWithinTheRatePassesWholeAFasterOneIsThinnedToIt) {
  MessageSampler sampler(on(25.0));
  // 20 Hz for 5 s, two frames per transport read (same arrival time): all pass.
  for (int i = 0; i < 100; ++i)
    sampler.onFrame(frameOf(pose(static_cast<std::uint32_t>(i * 50), 0.0f)), (i / 2) * 0.1);
  EXPECT_EQ(sampler.take().size(), 100u);
  EXPECT_EQ(sampler.counters().thinned, 0u);
  // 400 Hz for 5 s (a replay at x16 and more): about the burst plus 25 per second.
  for (int i = 0; i < 2000; ++i)
    sampler.onFrame(frameOf(pose(static_cast<std::uint32_t>(10000 + i * 2), 0.0f)),
                    10.0 + i * 0.0025);
  const auto thinned = sampler.take();
  EXPECT_GE(thinned.size(), 120u);
  EXPECT_LE(thinned.size(), 135u);
  for (std::size_t i = 1; i < thinned.size(); ++i)
    EXPECT_GT(thinned[i].robot_time_s, thinned[i - 1].robot_time_s);
}

TEST(MessageSampler, EachInstanceIsAStreamOfItsOwn) {
  MessageSampler sampler(on(25.0));
  // Eight sonars at 20 Hz each: 160 DISTANCE_SENSOR frames per second, all kept.
  for (int step = 0; step < 40; ++step) {
    for (std::uint8_t id = 0; id < 8; ++id) {
      mav::DistanceSensor d;
      d.time_boot_ms = static_cast<std::uint32_t>(step * 50);
      d.id = id;
      d.current_distance = static_cast<std::uint16_t>(100 + id);
      sampler.onFrame(frameOf(d), step * 0.05);
    }
  }
  const auto samples = sampler.take();
  ASSERT_EQ(samples.size(), 320u);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    ASSERT_TRUE(samples[i].instance.has_value());
    EXPECT_EQ(*samples[i].instance, i % 8);
    EXPECT_EQ(samples[i].values[3], 100.0 + static_cast<double>(i % 8));  // current_distance
  }
}

TEST(MessageSampler, UntimedMessagesTakeTheNewestTimeStampAndWaitForTheFirst) {
  MessageSampler sampler(on());
  sampler.onFrame(frameOf(mav::Heartbeat{}), 0.0);  // no robot time yet: waits for one
  EXPECT_EQ(sampler.counters().untimed, 1u);
  EXPECT_TRUE(sampler.take().empty());
  sampler.onFrame(frameOf(pose(4200, 1.0f)), 0.1);
  mav::SysStatus status;
  status.voltage_battery = 12600;
  sampler.onFrame(frameOf(status), 0.2);
  const auto samples = sampler.take();
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(samples[0].message->name, "HEARTBEAT");
  EXPECT_DOUBLE_EQ(samples[0].robot_time_s, 4.2);
  EXPECT_EQ(samples[1].message->name, "IRGS_POSE_2D");
  EXPECT_EQ(samples[2].message->name, "SYS_STATUS");
  EXPECT_DOUBLE_EQ(samples[2].robot_time_s, 4.2);
  // A robot reboot: its clock starts over and the untimed messages follow it.
  sampler.onFrame(frameOf(pose(300, 1.0f)), 1.0);
  sampler.onFrame(frameOf(status), 1.1);
  const auto after = sampler.take();
  ASSERT_EQ(after.size(), 2u);
  EXPECT_DOUBLE_EQ(after[1].robot_time_s, 0.3);
  EXPECT_EQ(sampler.counters().restarts, 1u);
  // reset() (link re-established): untimed messages wait for a time stamp again.
  sampler.reset();
  sampler.onFrame(frameOf(status), 2.0);
  EXPECT_TRUE(sampler.take().empty());
  sampler.onFrame(frameOf(pose(50, 1.0f)), 2.1);
  const auto reset = sampler.take();
  ASSERT_EQ(reset.size(), 2u);
  EXPECT_DOUBLE_EQ(reset[0].robot_time_s, 0.05);
}

TEST(MessageSampler, TheQueueKeepsTheNewestSamples) {
  MessageSamplerConfig config = on(1000.0);
  config.burst = 1000.0;
  config.max_pending = 10;
  MessageSampler sampler(config);
  for (int i = 0; i < 25; ++i)
    sampler.onFrame(frameOf(pose(static_cast<std::uint32_t>(i), static_cast<float>(i))), 0.0);
  const auto samples = sampler.take();
  ASSERT_EQ(samples.size(), 10u);
  EXPECT_EQ(samples.front().values[1], 15.0);  // x of the 16th frame
  EXPECT_EQ(sampler.counters().dropped, 15u);
}

}  // namespace
}  // namespace irgs::comms
