#include "app/robot/drive_guard.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace irgs::app {
namespace {

TEST(DriveGuard, KeepsAnAttachedPeerThroughTheGraceAndWhileItIsAlive) {
  DriveGuard guard(1.5);
  guard.peerAttached(10.0);
  EXPECT_TRUE(guard.peerActive(10.1, /*alive=*/false));  // has not said hello yet
  EXPECT_TRUE(guard.peerActive(11.4, false));
  EXPECT_TRUE(guard.peerActive(30.0, true));  // heartbeats keep it
  EXPECT_FALSE(guard.peerActive(31.0, false));
}

TEST(DriveGuard, ASilentPeerLetsTheNewcomerInWhichItsFirstBytesAttach) {
  DriveGuard guard(1.5);
  EXPECT_FALSE(guard.peerActive(0.0, false));  // nobody attached yet
  guard.peerBytes(5.0);                        // a UDP sender's first datagram attaches it
  EXPECT_TRUE(guard.peerActive(6.0, false));
  EXPECT_FALSE(guard.peerActive(7.0, false));  // silent past the grace: let go
  guard.peerBytes(7.0);                        // the newcomer's first datagram
  EXPECT_TRUE(guard.peerActive(7.5, false));   // its own grace, from 7.0
  guard.peerBytes(8.6);                        // later bytes of the same peer do not extend it
  EXPECT_FALSE(guard.peerActive(8.6, false));
}

TEST(DriveGuard, ReportsTheFirstRefusalAtOnceAndTheRestOncePerPeriod) {
  DriveGuard guard(1.5, 5.0);
  EXPECT_EQ(guard.refused("10.0.0.7:4001", 1.0), "refused client 10.0.0.7:4001 (1 total)");
  EXPECT_EQ(guard.refused("10.0.0.7:4002", 2.0), std::nullopt);
  EXPECT_EQ(guard.refused("10.0.0.8:4100", 3.0), std::nullopt);
  EXPECT_EQ(guard.dueReport(5.9), std::nullopt);
  EXPECT_EQ(guard.dueReport(6.0), "refused client 10.0.0.8:4100 (3 total)");
  EXPECT_EQ(guard.dueReport(20.0), std::nullopt);  // nothing new
  EXPECT_EQ(guard.refused("10.0.0.8:4101", 20.0), "refused client 10.0.0.8:4101 (4 total)");
  EXPECT_EQ(guard.refusedTotal(), 4u);
}

TEST(DriveGuard, AReportFitsAStatustext) {
  DriveGuard guard(1.5, 0.0);
  std::optional<std::string> report;
  for (int i = 0; i < 99999; ++i)
    report = guard.refused("255.255.255.255:65535", static_cast<double>(i));
  ASSERT_TRUE(report);
  EXPECT_LE(report->size(), 50u) << *report;
}

TEST(DriveGuard, ANonPositiveGraceIsRefused) {
  EXPECT_THROW(DriveGuard(0.0), std::invalid_argument);
  EXPECT_THROW(DriveGuard(1.0, -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace irgs::app
