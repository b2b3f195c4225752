#include "core/calibration/umbmark_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/calibration/profile_calibration.hpp"
#include "core/robot/robot_profile_file.hpp"

namespace irgs {
namespace {

RobotProfile p3dx() {
  const RobotProfileResult r = loadRobotProfileFile(std::filesystem::path(IRGS_SOURCE_DIR) /
                                                    "resources/robots/pioneer_p3dx.json");
  if (!r.ok())
    throw std::runtime_error("cannot load the P3-DX profile");
  return *r.profile;
}

double relativeError(double recovered, double injected) {
  return std::abs((recovered - 1.0) - (injected - 1.0)) / std::abs(injected - 1.0);
}

TEST(UmbmarkRun, ARobotWithoutErrorsReturnsToItsStart) {
  const RobotProfile robot = p3dx();
  UmbmarkRunConfig config;
  config.runs_per_direction = 1;
  const UmbmarkSimulation sim = runUmbmarkInSimulator(robot, {}, robot, config);
  ASSERT_TRUE(sim.ok);
  ASSERT_EQ(sim.trials.size(), 2u);
  for (const UmbmarkTrial& t : sim.trials) {
    EXPECT_TRUE(t.completed);
    EXPECT_LT(t.error_m.norm(), 0.01) << toString(t.direction);  // encoder quantisation only
    EXPECT_LT(t.odometry_final.position().norm(), 0.002);  // stopped where it believes it began
    EXPECT_GT(t.true_path.size(), 10u);
  }
  EXPECT_EQ(sim.runs().size(), 2u);
}

// Issue 6 acceptance: injected wheel-diameter and wheelbase errors are recovered within 10 % (of
// the error, E - 1) and applying the corrections cuts E_max,syst at least fivefold.
TEST(UmbmarkRun, InjectedErrorsAreRecoveredWithinTenPercentAndCorrectionCutsTheErrorFivefold) {
  const RobotProfile robot = p3dx();
  UmbmarkInjection injection;
  injection.wheel_diameter_ratio = 1.01;
  injection.wheelbase_scale = 1.03;
  injection.slip_stddev = 0.002;
  UmbmarkRunConfig config;
  config.seed = 11;
  const UmbmarkSetup setup{config.side_m, robot.drive.wheelbase_m};

  const UmbmarkSimulation before = runUmbmarkInSimulator(robot, injection, robot, config);
  ASSERT_TRUE(before.ok);
  const UmbmarkAnalysis a = analyseUmbmark(before.runs(), setup);
  ASSERT_TRUE(a.ok);
  RecordProperty("e_d", std::to_string(a.wheel_diameter_ratio));
  RecordProperty("e_b", std::to_string(a.wheelbase_ratio));
  EXPECT_LT(relativeError(a.wheel_diameter_ratio, injection.wheel_diameter_ratio), 0.1)
      << a.wheel_diameter_ratio;
  EXPECT_LT(relativeError(a.wheelbase_ratio, injection.wheelbase_scale), 0.1) << a.wheelbase_ratio;

  const RobotProfile corrected = applyUmbmark(robot, a, config.side_m);
  EXPECT_NEAR(corrected.drive.wheelbase_m, robot.drive.wheelbase_m * a.wheelbase_ratio, 1e-12);
  config.seed = 12;  // another day on the same floor
  const UmbmarkSimulation after = runUmbmarkInSimulator(robot, injection, corrected, config);
  ASSERT_TRUE(after.ok);
  const UmbmarkAnalysis b =
      analyseUmbmark(after.runs(), {config.side_m, corrected.drive.wheelbase_m});
  ASSERT_TRUE(b.ok);
  RecordProperty("e_max_before_m", std::to_string(a.e_max_syst_m));
  RecordProperty("e_max_after_m", std::to_string(b.e_max_syst_m));
  EXPECT_GT(a.e_max_syst_m, 0.5);  // the injected errors are visible
  EXPECT_LE(b.e_max_syst_m * 5.0, a.e_max_syst_m) << a.e_max_syst_m << " -> " << b.e_max_syst_m;
}

TEST(UmbmarkRun, SameSeedGivesTheSameRunsAndBadInputThrows) {
  const RobotProfile robot = p3dx();
  UmbmarkRunConfig config;
  config.runs_per_direction = 1;
  const UmbmarkInjection injection{1.005, 0.99, 0.002};
  const UmbmarkSimulation a = runUmbmarkInSimulator(robot, injection, robot, config);
  const UmbmarkSimulation b = runUmbmarkInSimulator(robot, injection, robot, config);
  ASSERT_EQ(a.trials.size(), b.trials.size());
  for (std::size_t i = 0; i < a.trials.size(); ++i)
    EXPECT_EQ(a.trials[i].error_m, b.trials[i].error_m);

  EXPECT_THROW(runUmbmarkInSimulator(robot, {0.0, 1.0, 0.0}, robot, config), std::invalid_argument);
  EXPECT_THROW(runUmbmarkInSimulator(robot, {1.0, NAN, 0.0}, robot, config), std::invalid_argument);
  UmbmarkRunConfig bad = config;
  bad.runs_per_direction = 0;
  EXPECT_THROW(runUmbmarkInSimulator(robot, {}, robot, bad), std::invalid_argument);
  bad = config;
  bad.side_m = -4.0;
  EXPECT_THROW(runUmbmarkInSimulator(robot, {}, robot, bad), std::invalid_argument);
  RobotProfile caster = robot;
  caster.drive.type = DriveType::kThreeCaster;
  EXPECT_THROW(runUmbmarkInSimulator(caster, {}, caster, config), std::invalid_argument);
}

TEST(UmbmarkRun, ARunThatCannotFinishInTimeIsReportedNotThrown) {
  const RobotProfile robot = p3dx();
  UmbmarkRunConfig config;
  config.runs_per_direction = 1;
  config.max_run_s = 5.0;
  const UmbmarkSimulation sim = runUmbmarkInSimulator(robot, {}, robot, config);
  EXPECT_FALSE(sim.ok);
  EXPECT_EQ(sim.diagnostics.size(), 2u);
  EXPECT_TRUE(sim.runs().empty());
}

}  // namespace
}  // namespace irgs
