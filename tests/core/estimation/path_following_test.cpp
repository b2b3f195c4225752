// Path following of paper 004 (digest 5.6): the reference path, the law (22)-(25), closed-loop
// convergence onto a curved path with perfect and with optical-mouse pose estimates.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/estimation/mouse_odometry.hpp"
#include "core/estimation/path_following.hpp"
#include "core/sim/diff_drive.hpp"
#include "core/sim/random.hpp"

namespace irgs {
namespace {

// An S-bend: straight, left quarter circle (R 1 m), right half circle (R 1.5 m), straight.
ReferencePath sBend() {
  ReferencePath path({0.0, 0.0, 0.0});
  path.addLine(1.0).addArc(1.0, kPi / 2).addArc(1.5, -kPi).addLine(2.0);
  return path;
}

TEST(ReferencePath, ChainsLinesAndArcsWithContinuousTangent) {
  const ReferencePath path = sBend();
  EXPECT_NEAR(path.length_m(), 1.0 + kPi / 2 + 1.5 * kPi + 2.0, 1e-12);
  // After the left quarter circle: at (2, 1) heading +90 deg; the right half circle ends at
  // (2 + 3, 1) heading -90 deg; then 2 m down.
  const ReferencePath::Point a = path.at(1.0 + kPi / 2);
  EXPECT_NEAR(a.pose.x, 2.0, 1e-12);
  EXPECT_NEAR(a.pose.y, 1.0, 1e-12);
  EXPECT_NEAR(a.pose.theta, kPi / 2, 1e-12);
  EXPECT_NEAR(path.end().x, 5.0, 1e-12);
  EXPECT_NEAR(path.end().y, -1.0, 1e-12);
  EXPECT_NEAR(path.end().theta, -kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(path.at(1.5).curvature, 1.0);
  EXPECT_DOUBLE_EQ(path.at(4.0).curvature, -1.0 / 1.5);
  // Sampling is continuous: no step longer than the sampling step.
  const auto samples = path.sample(0.01);
  for (std::size_t i = 1; i < samples.size(); ++i)
    EXPECT_LE((samples[i].pose.position() - samples[i - 1].pose.position()).norm(), 0.01 + 1e-12);
}

TEST(ReferencePath, ProjectionGivesTheSignedLateralDistance) {
  const ReferencePath path = sBend();
  const auto left = path.project({0.5, 0.2}, 0.0, path.length_m());
  EXPECT_NEAR(left.point.s_m, 0.5, 1e-12);
  EXPECT_NEAR(left.lateral_m, 0.2, 1e-12);  // left of the path is positive
  // Inside the left arc (centre (1, 1)), 0.3 m from the arc: on its left.
  const Vec2 inside = Vec2(1.0, 1.0) + 0.7 * Vec2(std::cos(-kPi / 4), std::sin(-kPi / 4));
  const auto in = path.project(inside, 0.0, 2.5);
  EXPECT_NEAR(in.lateral_m, 0.3, 1e-12);
  EXPECT_NEAR(in.point.s_m, 1.0 + kPi / 4, 1e-12);
  // Outside the right arc (centre (3.5, 1)) the point is on the path's left.
  const auto out = path.project({3.5, 1.0 + 1.8}, 2.0, 6.0);
  EXPECT_NEAR(out.lateral_m, 0.3, 1e-12);
}

TEST(ReferencePath, RejectsDegeneratePieces) {
  ReferencePath path({});
  EXPECT_THROW(path.addLine(0.0), std::invalid_argument);
  EXPECT_THROW(path.addArc(-1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(path.addArc(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(path.addArc(1.0, std::nan("")), std::invalid_argument);
  EXPECT_THROW(ReferencePath({std::nan(""), 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(PathFollower(ReferencePath({})), std::invalid_argument);  // empty
}

struct LoopResult {
  double max_tail_lateral_m = 0.0;  // |l| of the truth after the first 2 m of path
  double final_truth_lateral_m = 0.0;
  bool reached_end = false;
  bool lyapunov_non_increasing = true;
  double max_estimate_error_m = 0.0;
};

// Closed loop at 100 Hz: truth by exact arcs; the controller sees either the truth or the pose of
// two simulated mouse sensors (800 cpi, [A] noise) integrated with (13)-(15).
LoopResult runLoop(const Pose2& start, bool use_mice, const MouseNoise& noise = {}) {
  PathFollowerConfig config;
  config.speed_mps = 0.3;
  PathFollower follower(sBend(), config);
  const ReferencePath& path = follower.path();
  const MouseRig rig = symmetricMouseRig(0.2);
  MouseSensorSimulator right(rig.spec, rig.right, noise);
  MouseSensorSimulator left(rig.spec, rig.left, noise);
  SimRandom rng(11);
  MouseOdometry odo(rig, start);

  LoopResult r;
  Pose2 truth = start;
  double previous_v = std::numeric_limits<double>::infinity();
  const double dt = 0.01;
  for (int step = 0; step < 10000; ++step) {
    const Pose2 estimate = use_mice ? odo.pose() : truth;
    const PathFollowOutput out = follower.update(estimate);
    if (out.status == PathFollowStatus::kReachedEnd) {
      r.reached_end = true;
      break;
    }
    EXPECT_EQ(out.status, PathFollowStatus::kFollowing) << "step " << step;
    if (!use_mice) {
      const double v_lyap = 0.5 * config.k2 * out.lateral_m * out.lateral_m +
                            0.5 * out.heading_error_rad * out.heading_error_rad;
      if (v_lyap > previous_v + 1e-6)
        r.lyapunov_non_increasing = false;
      previous_v = v_lyap;
    }
    const BodyIncrement inc{out.command.linear_mps * dt, 0.0, out.command.angular_radps * dt};
    truth = integrateArc(truth, inc.dx_m, inc.dtheta_rad);
    odo.update(right.sample(inc, dt, 0.001, rng), left.sample(inc, dt, 0.001, rng));
    r.max_estimate_error_m =
        std::max(r.max_estimate_error_m, (odo.pose().position() - truth.position()).norm());
    const auto truth_proj = path.project(truth.position(), out.s_m - 0.5, out.s_m + 0.5);
    r.final_truth_lateral_m = truth_proj.lateral_m;
    if (out.s_m > 2.0)
      r.max_tail_lateral_m = std::max(r.max_tail_lateral_m, std::abs(truth_proj.lateral_m));
  }
  return r;
}

TEST(PathFollower, ConvergesOntoACurvedPathFromAnOffsetStart) {
  // 0.3 m right of the path, heading 25 deg off.
  const LoopResult r = runLoop({0.0, -0.3, degToRad(25.0)}, false);
  EXPECT_TRUE(r.reached_end);
  EXPECT_TRUE(r.lyapunov_non_increasing);  // V = k2 l^2/2 + theta~^2/2 never grows
  EXPECT_LT(r.max_tail_lateral_m, 0.02);
  EXPECT_LT(std::abs(r.final_truth_lateral_m), 1e-3);
}

TEST(PathFollower, ConvergesWhenSteeredByTwoMouseOdometry) {
  // [A] both sensors read the same floor 0.5 % long (an uncalibrated surface), plus 1 % random
  // per axis and interval.
  MouseNoise noise;
  noise.scale_error = 0.005;
  noise.relative_stddev = 0.01;
  const LoopResult r = runLoop({0.0, 0.25, degToRad(-20.0)}, true, noise);
  EXPECT_TRUE(r.reached_end);
  // The truth follows the path as well as the mice know where the robot is.
  // About 10 m of path: the common 0.5 % scale error alone gives 5 cm along the path.
  EXPECT_LT(r.max_estimate_error_m, 0.12);
  EXPECT_GT(r.max_estimate_error_m, 0.01);  // the noise is really there
  EXPECT_LT(r.max_tail_lateral_m, r.max_estimate_error_m + 0.02);
  std::printf("mouse-steered S-bend: max estimate error %.3f m, max |l| of the truth %.3f m\n",
              r.max_estimate_error_m, r.max_tail_lateral_m);
}

TEST(PathFollower, StopsOnInvalidOrSingularInput) {
  PathFollower follower(sBend());
  const PathFollowOutput bad = follower.update({std::nan(""), 0.0, 0.0});
  EXPECT_EQ(bad.status, PathFollowStatus::kInvalidInput);
  EXPECT_EQ(bad.command, VelocityCommand{});
  // At the centre of the left arc, 1 - c l = 0.
  PathFollower at_centre(ReferencePath({}).addArc(1.0, kPi));
  const PathFollowOutput singular = at_centre.update({0.0, 1.0, 0.0});
  EXPECT_EQ(singular.status, PathFollowStatus::kSingular);
  EXPECT_EQ(singular.command, VelocityCommand{});
  PathFollowerConfig config;
  config.k2 = 0.0;
  EXPECT_THROW(PathFollower(sBend(), config), std::invalid_argument);
}

TEST(PathFollower, TheLawMatchesTheFrenetModel) {
  // On the path with the right heading the command is the path's own turn: omega = v c.
  PathFollower follower(sBend());
  const ReferencePath::Point p = follower.path().at(1.5);
  follower.update(follower.path().at(1.2).pose);
  const PathFollowOutput out = follower.update(p.pose);
  EXPECT_NEAR(out.lateral_m, 0.0, 1e-12);
  EXPECT_NEAR(out.heading_error_rad, 0.0, 1e-12);
  EXPECT_NEAR(out.command.angular_radps, follower.config().speed_mps * 1.0, 1e-12);
  EXPECT_NEAR(out.sdot_mps, follower.config().speed_mps, 1e-12);  // (22)
}

}  // namespace
}  // namespace irgs
