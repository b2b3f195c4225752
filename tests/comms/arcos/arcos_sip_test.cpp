#include "comms/arcos/arcos_sip.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace irgs::comms::arcos {
namespace {

using Bytes = std::vector<std::uint8_t>;

// A hand-assembled SIP, byte by byte from the manual's table, so the parser is not only checked
// against our own encoder.
Bytes handMadeSip() {
  return Bytes{
      0x33,              // type: moving
      0x10, 0x27,        // XPOS 10000
      0xff, 0x7f,        // YPOS 32767
      0x00, 0x04,        // THPOS 1024 (90 deg at 2 pi/4096)
      0x2c, 0x01,        // L VEL 300
      0xd4, 0xfe,        // R VEL -300
      0x7e,              // BATTERY 12.6 V
      0x03, 0x05,        // STALL AND BUMPERS: left stall + rear bumper 1, right stall + front 2
      0x9c, 0xff,        // CONTROL -100
      0x03, 0x00,        // FLAGS: motors + sonar array 1
      0x2d,              // COMPASS
      0x02,              // SONAR COUNT
      0x00, 0xe8, 0x03,  // sonar 0: 1000
      0x07, 0x88, 0x13,  // sonar 7: 5000
      1,    2,    3,    4, 5,  // GRIP_STATE ANPORT ANALOG DIGIN DIGOUT
      0x7e, 0x04,              // BATTERYX10 1150
      0x01,                    // CHARGESTATE
      0xf6, 0xff,              // ROTVEL -10
      0x00, 0x80,              // FAULTFLAGS
  };
}

TEST(ArcosStandardSip, ParsesEveryFieldOfAHandAssembledPacket) {
  const auto result = parseStandardSip(handMadeSip());
  ASSERT_TRUE(result.sip) << result.error;
  const StandardSip& sip = *result.sip;
  EXPECT_TRUE(sip.moving());
  EXPECT_EQ(sip.x_raw, 10000);
  EXPECT_EQ(sip.y_raw, 32767);
  EXPECT_EQ(sip.theta_raw, 1024);
  EXPECT_EQ(sip.left_velocity, 300);
  EXPECT_EQ(sip.right_velocity, -300);
  EXPECT_EQ(sip.battery_decivolts, 126);
  EXPECT_TRUE(sip.leftStalled());
  EXPECT_TRUE(sip.rightStalled());
  EXPECT_EQ(sip.rearBumpers(), 0x01);
  EXPECT_EQ(sip.frontBumpers(), 0x02);
  EXPECT_EQ(sip.control, -100);
  EXPECT_TRUE(sip.motorsEnabled());
  EXPECT_EQ(sip.compass, 0x2d);
  ASSERT_EQ(sip.sonars.size(), 2u);
  EXPECT_EQ(sip.sonars[1], (SonarRangeRaw{7, 5000}));
  ASSERT_TRUE(sip.io);
  EXPECT_EQ((*sip.io)[3], 4);
  EXPECT_EQ(sip.battery_x10, 1150);
  EXPECT_EQ(sip.charge_state, 1);
  EXPECT_EQ(sip.rotational_velocity, -10);
  EXPECT_EQ(sip.fault_flags, 0x8000);
  EXPECT_EQ(encodeStandardSip(sip), handMadeSip());
}

TEST(ArcosStandardSip, RoundTripsWithEightAndSixteenSonars) {
  for (int count : {8, 16}) {
    StandardSip sip;
    sip.type = 0x32;
    sip.x_raw = 123;
    sip.theta_raw = -2000;
    for (int i = 0; i < count; ++i)
      sip.sonars.push_back({static_cast<std::uint8_t>(i), static_cast<std::uint16_t>(100 * i + 7)});
    sip.io = std::array<std::uint8_t, 5>{};
    sip.battery_x10 = 1230;
    const auto parsed = parseStandardSip(encodeStandardSip(sip));
    ASSERT_TRUE(parsed.sip) << parsed.error;
    EXPECT_EQ(*parsed.sip, sip) << count << " sonars";
  }
}

TEST(ArcosStandardSip, AcceptsAShortP2osPacketThatEndsAfterTheSonars) {
  Bytes bytes = handMadeSip();
  bytes.resize(20 + 6);  // through the two sonar readings
  const auto result = parseStandardSip(bytes);
  ASSERT_TRUE(result.sip) << result.error;
  EXPECT_EQ(result.sip->sonars.size(), 2u);
  EXPECT_FALSE(result.sip->io);
  EXPECT_FALSE(result.sip->battery_x10);
  // A partial IO group is ignored, not misread.
  bytes.push_back(9);
  EXPECT_FALSE(parseStandardSip(bytes).sip->io);
}

TEST(ArcosStandardSip, NamesTheFieldWhereATruncatedPacketEnds) {
  const Bytes bytes = handMadeSip();
  EXPECT_THAT(parseStandardSip(Bytes(bytes.begin(), bytes.begin() + 8)).error,
              ::testing::HasSubstr("L VEL"));
  EXPECT_THAT(parseStandardSip(Bytes(bytes.begin(), bytes.begin() + 22)).error,
              ::testing::HasSubstr("sonar reading 1 of 2"));
  EXPECT_THAT(parseStandardSip(Bytes{0x20, 0, 0}).error, ::testing::HasSubstr("not a standard"));
  EXPECT_FALSE(parseStandardSip(Bytes{}).sip);
}

TEST(ArcosStandardSip, RejectsSonarCountsAndIndicesOutOfRange) {
  Bytes bytes = handMadeSip();
  bytes[19] = 40;
  EXPECT_THAT(parseStandardSip(bytes).error, ::testing::HasSubstr("40 sonar readings"));
  bytes = handMadeSip();
  bytes[20] = 33;
  EXPECT_THAT(parseStandardSip(bytes).error, ::testing::HasSubstr("NUMBER 33"));
}

TEST(ArcosOdometryUnwrapper, FollowsTheFifteenBitWrapAroundBothWays) {
  OdometryUnwrapper x;
  EXPECT_EQ(x.update(32700), 0);
  EXPECT_EQ(x.update(32767), 67);
  EXPECT_EQ(x.update(40), 67 + 41);          // wrapped forwards past 32767 -> 0
  EXPECT_EQ(x.update(32760), 67 + 41 - 48);  // and back again
  // The high bit is not part of the counter.
  EXPECT_EQ(x.update(32760 | 0x8000), 67 + 41 - 48);
  x.reset();
  EXPECT_EQ(x.update(5), 0);
}

TEST(ArcosSync2Reply, CarriesNameClassAndSubclass) {
  const RobotIdentity identity{"MobileSim", "Pioneer", "p3dx"};
  const auto parsed = parseSync2Reply(encodeSync2Reply(identity));
  ASSERT_TRUE(parsed);
  EXPECT_EQ(*parsed, identity);
  EXPECT_FALSE(parseSync2Reply(Bytes{1, 'a', 0}));
  EXPECT_FALSE(parseSync2Reply(Bytes{2, 'a', 0}));  // only one field
  // A missing last terminator is tolerated.
  EXPECT_EQ(parseSync2Reply(Bytes{2, 'a', 0, 'b', 0, 'c'})->subclass, "c");
}

}  // namespace
}  // namespace irgs::comms::arcos
