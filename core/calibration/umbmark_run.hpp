#pragma once
// UMBmark in the simulator: a robot with injected wheel-diameter and wheelbase errors drives the
// square clockwise and counter-clockwise n times each, closed-loop on its own odometry (as a real
// robot would: it stops where it believes it started), and the return errors are taken against
// the simulator's truth.
//
// Two profiles take part. `physical` is the robot as built (its nominal geometry); the injected
// errors are relative to it: left/right wheel travel = 2/(E_d+1), 2 E_d/(E_d+1) of the nominal
// (mean wheel right), true wheelbase = S * physical.drive.wheelbase_m. `believed` is the profile
// the odometry uses: wheel_radius_m, encoder conversion, wheelbase_m and the per-wheel scales of
// its "calibration.odometry" (profile_calibration.hpp). Before calibration both are the same
// profile; after it, `believed` is the corrected profile and the same physical robot re-runs.
//
// Odometry: integrated here from the simulator's encoder ticks with the believed parameters
// (the simulator's own odometry always uses the nominal profile).

#include <cstdint>
#include <string>
#include <vector>

#include "core/calibration/umbmark.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

struct UmbmarkInjection {
  double wheel_diameter_ratio = 1.0;  // E_d = D_R / D_L of the physical robot
  double wheelbase_scale = 1.0;       // true wheelbase / physical.drive.wheelbase_m
  double slip_stddev = 0.0;           // relative random slip per step, per wheel
};

struct UmbmarkRunConfig {
  double side_m = 4.0;  // the paper's 4 m square
  int runs_per_direction = 5;
  double speed_mps = 0.2;        // cruise speed on the legs (capped by the profile's limit)
  double turn_rate_radps = 0.5;  // on-the-spot turns (capped by the profile's limit)
  double dt_s = 0.01;
  std::uint64_t seed = 1;
  double max_run_s = 900.0;     // a run longer than this is abandoned (reported, not thrown)
  double path_period_s = 0.25;  // how often the recorded paths are sampled
};

struct UmbmarkTrial {
  UmbmarkDirection direction = UmbmarkDirection::kClockwise;
  bool completed = false;
  double duration_s = 0.0;
  Pose2 true_final;             // start frame (the run starts at the origin facing +x)
  Pose2 odometry_final;         // what the robot believed at the end
  Vec2 error_m = Vec2::Zero();  // true - believed final position
  std::vector<Vec2> true_path;
  std::vector<Vec2> odometry_path;
};

struct UmbmarkSimulation {
  bool ok = false;                   // every trial completed
  std::vector<UmbmarkTrial> trials;  // cw then ccw alternating, as on a real floor
  std::vector<std::string> diagnostics;

  std::vector<UmbmarkRun> runs() const;  // the completed trials, for analyseUmbmark
};

// Throws std::invalid_argument for a non-differential or invalid profile, invalid injection
// (ratios <= 0, non-finite, > 20 % off) or config (side <= 0, runs < 1 or > 100, dt not in
// (0, 0.1], speeds <= 0).
UmbmarkSimulation runUmbmarkInSimulator(const RobotProfile& physical,
                                        const UmbmarkInjection& injection,
                                        const RobotProfile& believed,
                                        const UmbmarkRunConfig& config = {});

}  // namespace irgs
