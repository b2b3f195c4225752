#include "comms/link/command_manager.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace irgs::comms {
namespace {

namespace mav = mavlink;

constexpr std::uint8_t kGcs = 255;
constexpr std::uint8_t kGcsComp = 190;

mav::CommandLong stopCommand() {
  mav::CommandLong c;
  c.target_system = 1;
  c.target_component = 1;
  c.command = static_cast<std::uint16_t>(mav::MavCmd::kIrgsStop);
  return c;
}

mav::CommandAck ackFor(const mav::CommandLong& c, mav::MavResult result) {
  mav::CommandAck a;
  a.command = c.command;
  a.result = static_cast<std::uint8_t>(result);
  return a;
}

TEST(CommandManager, SecondCommandWithTheSameIdCancelsTheFirst) {
  CommandManager m;
  std::vector<mav::CommandLong> out;
  m.submit(stopCommand(), {}, 0.0, out);
  m.submit(stopCommand(), {}, 0.1, out);
  EXPECT_EQ(out.size(), 2u);
  EXPECT_EQ(m.pending(), 1u);
  const auto done = m.takeCompleted();
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].result.outcome, CommandOutcome::kCancelled);
  EXPECT_NE(done[0].result.message.find("superseded"), std::string::npos);
}

TEST(CommandManager, AckFromAnotherSystemOrForAnotherGcsIsIgnored) {
  CommandManager m;
  std::vector<mav::CommandLong> out;
  m.submit(stopCommand(), {}, 0.0, out);
  auto ack = ackFor(stopCommand(), mav::MavResult::kAccepted);
  EXPECT_FALSE(m.onAck(ack, 7, kGcs, kGcsComp, 0.1));  // system 7 was not asked
  ack.target_system = 42;                              // meant for another ground station
  EXPECT_FALSE(m.onAck(ack, 1, kGcs, kGcsComp, 0.1));
  ack.target_system = kGcs;
  EXPECT_TRUE(m.onAck(ack, 1, kGcs, kGcsComp, 0.1));
  EXPECT_EQ(m.pending(), 0u);
}

TEST(CommandManager, InProgressStopsRetriesAndWaitsForTheFinalAck) {
  CommandConfig config;
  config.in_progress_timeout_s = 5.0;
  CommandManager m(config);
  std::vector<mav::CommandLong> out;
  m.submit(stopCommand(), {}, 0.0, out);
  EXPECT_TRUE(m.onAck(ackFor(stopCommand(), mav::MavResult::kInProgress), 1, kGcs, kGcsComp, 0.2));
  out.clear();
  for (double t = 0.25; t < 4.0; t += 0.05)
    m.tick(t, out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(m.pending(), 1u);
  EXPECT_TRUE(m.onAck(ackFor(stopCommand(), mav::MavResult::kAccepted), 1, kGcs, kGcsComp, 4.0));
  const auto done = m.takeCompleted();
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].result.outcome, CommandOutcome::kAccepted);
}

TEST(CommandManager, InProgressWithoutAFinalAckTimesOut) {
  CommandConfig config;
  config.in_progress_timeout_s = 1.0;
  CommandManager m(config);
  std::vector<mav::CommandLong> out;
  m.submit(stopCommand(), {}, 0.0, out);
  m.onAck(ackFor(stopCommand(), mav::MavResult::kInProgress), 1, kGcs, kGcsComp, 0.1);
  m.tick(1.05, out);
  EXPECT_EQ(m.pending(), 1u);
  m.tick(1.15, out);
  const auto done = m.takeCompleted();
  ASSERT_EQ(done.size(), 1u);
  EXPECT_EQ(done[0].result.outcome, CommandOutcome::kTimedOut);
  EXPECT_NE(done[0].result.message.find("IN_PROGRESS"), std::string::npos);
}

TEST(CommandManager, RejectsNonsenseConfiguration) {
  EXPECT_THROW(CommandManager(CommandConfig{.retry_s = 0.0}), std::invalid_argument);
  EXPECT_THROW(CommandManager(CommandConfig{.max_attempts = 0}), std::invalid_argument);
}

TEST(CommandManager, NamesKnownAndUnknownCommandsAndResults) {
  EXPECT_EQ(commandName(static_cast<std::uint16_t>(mav::MavCmd::kIrgsMoveDistance)),
            "IRGS_MOVE_DISTANCE");
  EXPECT_EQ(commandName(9999), "MAV_CMD 9999");
  EXPECT_EQ(resultName(static_cast<std::uint8_t>(mav::MavResult::kDenied)), "DENIED");
  EXPECT_EQ(resultName(200), "MAV_RESULT 200");
}

}  // namespace
}  // namespace irgs::comms
