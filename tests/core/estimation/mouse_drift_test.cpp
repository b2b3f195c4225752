// Paper 004 in simulation (issue 5 acceptance): the Type (2,0) robot of
// resources/robots/mouse_type20_004.json drives a curved path in the Simulator, steered by the
// path follower (22)-(25); on the same run, the simulator's wheel-encoder odometry (with its
// scale-factor and slip errors) and two simulated optical-mouse sensors integrated by (1)-(15)
// are compared with the true pose. Drift per metre = final position error / distance driven.
// Numbers: docs/localization.md.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "core/estimation/mouse_odometry.hpp"
#include "core/estimation/path_following.hpp"
#include "core/robot/robot_profile_file.hpp"
#include "core/sim/simulator.hpp"

namespace irgs {
namespace {

struct DriftResult {
  double distance_m = 0.0;
  double encoder_final_m = 0.0, encoder_max_m = 0.0, encoder_heading_deg = 0.0;
  double mouse_final_m = 0.0, mouse_max_m = 0.0, mouse_heading_deg = 0.0;
  double max_lateral_m = 0.0;  // of the truth, after the first metre
  bool finished = false;
};

// Three laps of a 2 m x 2 m-radius stadium (about 31 m), 0.3 m/s.
ReferencePath stadiumLaps(const Pose2& start) {
  ReferencePath path(start);
  for (int lap = 0; lap < 3; ++lap)
    path.addLine(2.0).addArc(1.0, kPi).addLine(2.0).addArc(1.0, kPi);
  return path;
}

DriftResult run(std::uint64_t seed, const MouseSensorSpec& spec, const MouseNoise& noise) {
  const RobotProfileResult loaded = loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) +
                                                         "/resources/robots/mouse_type20_004.json");
  EXPECT_TRUE(loaded.ok());
  MouseRig rig = *mouseRigFromProfile(*loaded.profile).rig;
  rig.spec = spec;

  SimConfig config;
  config.seed = seed;
  // The encoder errors of the paper-000 run test (1 % / 0.4 % wheel scale, 0.2 % slip).
  config.odometry.left_scale = 1.01;
  config.odometry.right_scale = 1.004;
  config.odometry.slip_stddev = 0.002;
  Simulator sim(WorldMap{}, *loaded.profile, config);
  const Pose2 start{0.0, 0.0, 0.0};
  sim.resetPose(start);

  PathFollowerConfig follow;
  follow.speed_mps = 0.3;
  PathFollower follower(stadiumLaps(start), follow);
  MouseSensorSimulator right(rig.spec, rig.right, noise), left(rig.spec, rig.left, noise);
  SimRandom mouse_rng = SimRandom::stream(seed, 100);
  MouseOdometry mice(rig, start);

  DriftResult r;
  TelemetrySample sample;
  Pose2 previous = start;
  const double dt = sim.config().dt_s;
  for (int step = 0; step < 60000; ++step) {
    const PathFollowOutput out = follower.update(sim.truePose());
    if (out.status == PathFollowStatus::kReachedEnd) {
      r.finished = true;
      break;
    }
    if (out.s_m > 1.0)
      r.max_lateral_m = std::max(r.max_lateral_m, std::abs(out.lateral_m));
    sim.setCommand(out.command);
    sim.step(sample);
    const Pose2 truth = *sample.true_pose;
    const BodyIncrement inc = incrementBetween(previous, truth);
    r.distance_m += std::hypot(truth.x - previous.x, truth.y - previous.y);
    previous = truth;
    // 1 mm floor gap, well inside the 2 mm limit.
    mice.update(right.sample(inc, dt, 0.001, mouse_rng), left.sample(inc, dt, 0.001, mouse_rng));
    r.encoder_max_m =
        std::max(r.encoder_max_m, (sample.odometry_pose.position() - truth.position()).norm());
    r.mouse_max_m = std::max(r.mouse_max_m, (mice.pose().position() - truth.position()).norm());
  }
  const Pose2 truth = sim.truePose();
  r.encoder_final_m = (sim.odometryPose().position() - truth.position()).norm();
  r.mouse_final_m = (mice.pose().position() - truth.position()).norm();
  r.encoder_heading_deg = radToDeg(std::abs(wrapAngle(sim.odometryPose().theta - truth.theta)));
  r.mouse_heading_deg = radToDeg(std::abs(wrapAngle(mice.pose().theta - truth.theta)));
  return r;
}

void print(const char* label, std::uint64_t seed, const DriftResult& r) {
  std::printf(
      "%s seed %llu: %.1f m driven; encoder final %.3f m (%.2f mm/m, max %.3f m, heading %.2f "
      "deg); mice final %.4f m (%.3f mm/m, max %.4f m, heading %.3f deg)\n",
      label, static_cast<unsigned long long>(seed), r.distance_m, r.encoder_final_m,
      1000.0 * r.encoder_final_m / r.distance_m, r.encoder_max_m, r.encoder_heading_deg,
      r.mouse_final_m, 1000.0 * r.mouse_final_m / r.distance_m, r.mouse_max_m, r.mouse_heading_deg);
}

TEST(MouseOdometryDrift, IdealMiceDriftFarLessPerMetreThanEncodersOnTheSameRun) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const DriftResult r = run(seed, MouseSensorSpec{}, MouseNoise{});  // 800 cpi quantisation
    print("ideal mice (800 cpi)", seed, r);
    ASSERT_TRUE(r.finished);
    EXPECT_GT(r.distance_m, 30.0);
    EXPECT_LT(r.max_lateral_m, 0.02);  // the follower tracks the path with the true pose
    EXPECT_GT(r.encoder_final_m / r.distance_m, 0.005);  // > 5 mm/m: the encoder errors bite
    EXPECT_LT(r.mouse_final_m / r.distance_m, 1e-4);     // < 0.1 mm/m: only quantisation
    EXPECT_LT(r.mouse_final_m, 0.01 * r.encoder_final_m);
  }
}

TEST(MouseOdometryDrift, NoisyMiceAtFourHundredCpiStillBeatTheEncoders) {
  MouseSensorSpec spec;
  spec.counts_per_inch = 400.0;
  MouseNoise noise;  // [A] common 0.5 % surface scale error, 1 % random per axis and interval
  noise.scale_error = 0.005;
  noise.relative_stddev = 0.01;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const DriftResult r = run(seed, spec, noise);
    print("noisy mice (400 cpi)", seed, r);
    ASSERT_TRUE(r.finished);
    EXPECT_GT(r.mouse_final_m, 1e-3);  // the noise is really there
    EXPECT_LT(r.mouse_final_m, 0.5 * r.encoder_final_m);
  }
}

}  // namespace
}  // namespace irgs
