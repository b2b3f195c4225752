// Checks the bundled default robot against the thesis (paper 003, digest section 4.2).
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "core/robot/robot_profile_file.hpp"

namespace irgs {
namespace {

RobotProfile loadThesisRobot() {
  const auto result =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/thesis_robot.json");
  for (const auto& d : result.diagnostics)
    ADD_FAILURE() << d.toString();
  return result.profile.value_or(RobotProfile{});
}

TEST(ThesisRobot, LoadsWithoutDiagnostics) {
  EXPECT_EQ(loadThesisRobot().name, "thesis_robot");
}

// Every bundled robot profile loads clean: a warning at every start would teach users to
// ignore warnings (the ARCOS section of the Pioneer profiles is a documented key).
TEST(BundledRobots, EveryProfileLoadsWithoutDiagnostics) {
  int profiles = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(IRGS_SOURCE_DIR) + "/resources/robots")) {
    if (entry.path().extension() != ".json")
      continue;
    ++profiles;
    const auto result = loadRobotProfileFile(entry.path());
    EXPECT_TRUE(result.profile.has_value()) << entry.path();
    for (const auto& d : result.diagnostics)
      ADD_FAILURE() << d.toString();
  }
  EXPECT_GE(profiles, 7);
}

TEST(ThesisRobot, IsARegularOctagonOnTheWheelAxle) {
  const RobotProfile p = loadThesisRobot();
  ASSERT_EQ(p.body_outline.size(), 8u);
  const double circumradius = 0.15 / std::cos(degToRad(22.5));
  for (const Vec2& v : p.body_outline)
    EXPECT_NEAR(v.norm(), circumradius, 1e-5);
  EXPECT_NEAR(p.bodyRadius(), circumradius, 1e-5);
  EXPECT_EQ(p.drive.type, DriveType::kDifferential);
  EXPECT_DOUBLE_EQ(p.drive.ticksPerWheelRad(), 2700.0);  // 27 pulse/rad, 1:100
}

TEST(ThesisRobot, HasEightSonarsInCoLocatedPairsAtNinetyDegrees) {
  const RobotProfile p = loadThesisRobot();
  ASSERT_EQ(p.sonars.size(), 8u);
  int forward = 0;
  for (std::size_t i = 0; i < 8; i += 2) {
    const SonarSpec& a = p.sonars[i];
    const SonarSpec& b = p.sonars[i + 1];
    EXPECT_EQ(a.mount.x, b.mount.x);
    EXPECT_EQ(a.mount.y, b.mount.y);
    EXPECT_NEAR(std::abs(wrapAngle(a.mount.theta - b.mount.theta)), kPi / 2.0, 1e-12);
    forward += (a.mount.theta == 0.0) + (b.mount.theta == 0.0);
  }
  EXPECT_EQ(forward, 4);  // four forward-looking sensors, four sideways
  // The side pairs (indices 4..7) are mounted behind the front pairs (0..3).
  EXPECT_LT(p.sonars[4].mount.x, p.sonars[0].mount.x);
  // All look into the front half plane (-90 .. +90 degrees) and reach 4 m.
  for (const SonarSpec& s : p.sonars) {
    EXPECT_LE(std::abs(s.mount.theta), kPi / 2.0 + 1e-12);
    EXPECT_DOUBLE_EQ(s.max_range_m, 4.0);
  }
}

TEST(ThesisRobot, HasNinePhotoSensorsOnePerFacePlusOneAtTheRear) {
  const RobotProfile p = loadThesisRobot();
  ASSERT_EQ(p.proximity.size(), 9u);
  std::set<long> headings;
  int rear = 0;
  for (const ProximitySpec& s : p.proximity) {
    headings.insert(std::lround(radToDeg(s.mount.theta)));
    rear += std::abs(std::abs(s.mount.theta) - kPi) < 1e-9;
  }
  EXPECT_EQ(headings.size(), 8u);
  EXPECT_EQ(rear, 2);
}

TEST(ThesisRobot, HasSixBumpersTwoOnEachFrontFace) {
  const RobotProfile p = loadThesisRobot();
  ASSERT_EQ(p.bumpers.size(), 6u);
  std::multiset<long> normals;
  for (const BumperSpec& b : p.bumpers)
    normals.insert(std::lround(radToDeg(b.normal_rad)));
  EXPECT_EQ(normals, (std::multiset<long>{-45, -45, 0, 0, 45, 45}));
}

TEST(ThesisRobot, DocumentsItsAssumptionsInNotes) {
  const RobotProfile p = loadThesisRobot();
  ASSERT_TRUE(p.extra.contains("notes"));
  EXPECT_NE(p.extra["notes"].dump().find("ASSUMPTION"), std::string::npos);
}

}  // namespace
}  // namespace irgs
