#include "core/calibration/profile_calibration.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>

#include "core/robot/robot_profile_file.hpp"

namespace irgs {
namespace {

RobotProfile loadBundled() {
  const RobotProfileResult r = loadRobotProfileFile(std::filesystem::path(IRGS_SOURCE_DIR) /
                                                    "resources/robots/pioneer_p3dx.json");
  if (!r.ok())
    throw std::runtime_error("cannot load the P3-DX profile");
  return *r.profile;
}

UmbmarkAnalysis analysisOf(double e_d, double e_b, double wheelbase_m) {
  const UmbmarkSetup setup{4.0, wheelbase_m};
  const std::vector<UmbmarkRun> runs = {
      {UmbmarkDirection::kClockwise,
       predictUmbmarkError(UmbmarkDirection::kClockwise, setup, e_d, e_b)},
      {UmbmarkDirection::kCounterClockwise,
       predictUmbmarkError(UmbmarkDirection::kCounterClockwise, setup, e_d, e_b)}};
  return analyseUmbmark(runs, setup);
}

TEST(ProfileCalibration, CorrectedProfileIsWrittenAndReadBackWithoutWarnings) {
  const RobotProfile robot = loadBundled();
  const RobotProfile odo =
      applyUmbmark(robot, analysisOf(1.01, 1.03, robot.drive.wheelbase_m), 4.0);
  GyroCalibration g;
  g.bias = {-0.01, 0.002, 0.0};
  g.scale.a1 = 0.0125;
  g.scale.a2_per_dps = 7e-6;
  g.scale.a3_per_dps2 = 2.7e-6;
  const RobotProfile both = applyGyroCalibration(odo, g);

  const auto dir = std::filesystem::temp_directory_path() /
                   ("irgs_profile_calibration_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const auto path = dir / "sub" / "p3dx_calibrated.json";
  ASSERT_FALSE(saveCalibratedProfile(both, path).has_value());
  const RobotProfileResult back = loadRobotProfileFile(path);
  ASSERT_TRUE(back.ok());
  for (const Diagnostic& d : back.diagnostics)  // the bundled file's own keys may warn
    EXPECT_EQ(d.field.find("calibration"), std::string::npos) << d.toString();
  EXPECT_NEAR(back.profile->drive.wheelbase_m, robot.drive.wheelbase_m * 1.03, 1e-9);
  const ProfileOdometry o = profileOdometry(*back.profile);
  EXPECT_TRUE(o.error.empty());
  EXPECT_NEAR(o.odometry.right_wheel_scale / o.odometry.left_wheel_scale, 1.01, 1e-9);
  const auto gyro = profileGyroCalibration(*back.profile);
  ASSERT_TRUE(gyro.has_value());
  EXPECT_EQ(gyro->scale.a3_per_dps2, 2.7e-6);
  EXPECT_EQ(gyro->bias.c1_dps_per_c, 0.002);
  std::filesystem::remove_all(dir);
}

TEST(ProfileCalibration, AnUncalibratedProfileHasUnitScalesAndAMalformedOneIsReported) {
  RobotProfile robot = loadBundled();
  EXPECT_EQ(profileOdometry(robot).odometry.left_wheel_scale, 1.0);
  EXPECT_FALSE(profileGyroCalibration(robot).has_value());
  robot.extra["calibration"] = {{"odometry", {{"left_wheel_scale", "big"}}}};
  const ProfileOdometry o = profileOdometry(robot);
  EXPECT_FALSE(o.error.empty());
  EXPECT_EQ(o.odometry.left_wheel_scale, 1.0);
  UmbmarkAnalysis failed;
  EXPECT_THROW(applyUmbmark(robot, failed, 4.0), std::invalid_argument);
  GyroCalibration nan;
  nan.scale.a1 = NAN;
  EXPECT_THROW(applyGyroCalibration(robot, nan), std::invalid_argument);
  EXPECT_TRUE(saveCalibratedProfile(robot, "").has_value());
  EXPECT_TRUE(saveCalibratedProfile(robot, "/proc/irgs_no_such/x.json").has_value());
}

}  // namespace
}  // namespace irgs
