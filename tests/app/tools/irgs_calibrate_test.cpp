// irgs-calibrate end to end: the executable runs the procedure headless and writes a profile
// that loads and carries the corrections (issue 6 acceptance, on the command line).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/calibration/profile_calibration.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/gyro_sim.hpp"

namespace irgs {
namespace {

struct ToolRun {
  int code = -1;
  std::string out;
};

ToolRun calibrate(const std::string& args) {
  const std::string command = std::string(IRGS_CALIBRATE) + " " + args + " 2>&1";
  ToolRun r;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr)
    return r;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    r.out.append(buffer, n);
  const int status = ::pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "irgs_calibrate_test";
  std::filesystem::create_directories(dir);
  std::filesystem::remove(dir / name);
  return dir / name;
}

const std::string kP3dx = std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_p3dx.json";

TEST(IrgsCalibrate, UmbmarkInTheSimulatorRecoversTheInjectedErrorsAndWritesTheProfile) {
  const auto out = scratch("p3dx_umbmark.json");
  const ToolRun r =
      calibrate("umbmark --profile " + kP3dx +
                " --inject ed=1.01,eb=1.03,slip=0.002 --runs 5 --seed 11 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("E_max,syst improvement: x"), std::string::npos) << r.out;
  const RobotProfileResult loaded = loadRobotProfileFile(out);
  ASSERT_TRUE(loaded.ok()) << r.out;
  const RobotProfileResult original = loadRobotProfileFile(kP3dx);
  ASSERT_TRUE(original.ok());
  const ProfileOdometry odometry = profileOdometry(*loaded.profile);
  ASSERT_TRUE(odometry.error.empty()) << odometry.error;
  // E_d = D_R / D_L = 1.01: the corrected odometry counts the right wheel's travel 1.01 times
  // the left's (paper eq. 17: c_R / c_L = E_d).
  const double recovered_ed =
      odometry.odometry.right_wheel_scale / odometry.odometry.left_wheel_scale;
  EXPECT_NEAR(recovered_ed, 1.01, 0.1 * 0.01) << r.out;
  const double recovered_eb =
      loaded.profile->drive.wheelbase_m / original.profile->drive.wheelbase_m;
  EXPECT_NEAR(recovered_eb, 1.03, 0.1 * 0.03) << r.out;
}

TEST(IrgsCalibrate, UmbmarkFromMeasuredReturnErrorsAndBadInput) {
  const auto measured = scratch("measured.csv");
  {
    std::ofstream f(measured);
    f << "# direction, x_m, y_m\ncw, 0.30, -0.85\ncw, 0.32, -0.87\nccw, 0.33, 0.86\n"
         "ccw, 0.29, 0.84\n";
  }
  const auto out = scratch("p3dx_measured.json");
  const ToolRun r = calibrate("umbmark --profile " + kP3dx + " --measured " + measured.string() +
                              " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(loadRobotProfileFile(out).ok());

  EXPECT_EQ(calibrate("umbmark --profile " + kP3dx).code, 2);  // no --out
  EXPECT_EQ(calibrate("umbmark --profile " + kP3dx + " --inject ed=x --out " + out.string()).code,
            2);
  EXPECT_EQ(calibrate("spin --profile " + kP3dx).code, 2);
  EXPECT_EQ(calibrate("umbmark --profile /no/such.json --out " + out.string()).code, 1);
}

TEST(IrgsCalibrate, GyroInTheSimulatorRecoversTheInjectedCoefficientsAndWritesTheProfile) {
  const auto out = scratch("p3dx_gyro.json");
  const ToolRun r =
      calibrate("gyro --profile " + kP3dx + " --inject autogyro --seed 5 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  const RobotProfileResult loaded = loadRobotProfileFile(out);
  ASSERT_TRUE(loaded.ok());
  const std::optional<GyroCalibration> c = profileGyroCalibration(*loaded.profile);
  ASSERT_TRUE(c.has_value()) << r.out;
  const GyroErrorModel injected = autogyroErrorModel();
  EXPECT_NEAR(c->scale.a1, injected.sf_a1, 0.1 * injected.sf_a1);
  EXPECT_NEAR(c->scale.a2_per_dps, injected.sf_a2_per_dps, 0.1 * injected.sf_a2_per_dps);
  EXPECT_NEAR(c->scale.a3_per_dps2, injected.sf_a3_per_dps2, 0.1 * injected.sf_a3_per_dps2);
  EXPECT_NEAR(c->bias.c1_dps_per_c, injected.bias_c1_dps_per_c, 0.1 * injected.bias_c1_dps_per_c);
}

}  // namespace
}  // namespace irgs
