#include "core/motion/turn_control.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/robot/robot_profile_file.hpp"
#include "core/sim/sim_presets.hpp"
#include "core/sim/simulator.hpp"
#include "tests/core/behaviour/behaviour_test_support.hpp"
#include "tests/core/behaviour/sampled_link.hpp"

namespace irgs {
namespace {

RobotProfile amigo() {
  auto loaded =
      loadRobotProfileFile(std::string(IRGS_SOURCE_DIR) + "/resources/robots/pioneer_amigo.json");
  if (!loaded.profile)
    throw std::runtime_error("cannot load the AmigoBot profile");
  return *loaded.profile;
}

constexpr double kTurnRate_radps = degToRad(60.0);  // WallFollowConfig's default

// One on-the-spot turn to a heading, then finished: with turnStep, or with the rule both
// behaviours used before it (turnRate's floored rate until turnDone and settled).
class SpotTurn : public Behaviour {
 public:
  SpotTurn(double turn_rad, bool legacy) : turn_rad_(turn_rad), legacy_(legacy) {}
  VelocityCommand onSample(const TelemetrySample& s) override {
    if (!target_)
      target_ = wrapAngle(s.odometry_pose.theta + turn_rad_);
    const double w = s.measured_velocity.angular_radps;
    if (legacy_) {
      done_ = turnDone(s.odometry_pose.theta, *target_) && std::abs(w) < 0.1;
      return done_
                 ? VelocityCommand{}
                 : VelocityCommand{0.0, turnRate(s.odometry_pose.theta, *target_, kTurnRate_radps)};
    }
    const TurnStep step = turnStep(progress_, s.odometry_pose.theta, *target_, w, kTurnRate_radps);
    done_ = step.done;
    return {0.0, step.angular_radps};
  }
  BehaviourStatus status() const override { return {"turn", 0.0, done_, false, {}}; }
  std::string_view name() const override { return "spot turn"; }
  double target() const { return *target_; }

 private:
  double turn_rad_;
  bool legacy_;
  std::optional<double> target_;
  TurnProgress progress_;
  bool done_ = false;
};

struct TurnResult {
  test::SampledLinkRun run;
  double rest_error_rad = 0.0;  // heading error once the robot has come to rest after the turn
};

TurnResult turnOverLink(const RobotProfile& robot, double turn_rad, bool legacy,
                        test::SampledLink link, double budget_s) {
  const WorldMap map = test::loadBundledMap("thesis_arena_250");  // start pose in the open
  Simulator sim(map, robot, idealSimConfig());
  sim.resetPose(map.start);
  SpotTurn turn(turn_rad, legacy);
  TurnResult out;
  out.run = test::runOverSampledLink(sim, turn, link, budget_s);
  sim.setCommand({});  // the last answer of a finished turn
  for (int i = 0; i < 200; ++i)
    sim.step();
  out.rest_error_rad = wrapAngle(turn.target() - sim.odometryPose().theta);
  return out;
}

TEST(MotionTurnStep, FloorsUntilTheTargetIsCrossedAndCommandsNothingInsideTheToleranceAfter) {
  const double tol = degToRad(1.0);
  const double max_rate = 0.5;
  TurnProgress p;
  // Far out: proportional, clamped to the rate limit.
  EXPECT_DOUBLE_EQ(turnStep(p, 0.0, 1.0, 0.0, max_rate).angular_radps, 0.5);
  EXPECT_DOUBLE_EQ(turnStep(p, 0.9, 1.0, 0.3, max_rate).angular_radps, 0.3);
  // Just outside: the floor, toward the target.
  EXPECT_DOUBLE_EQ(turnStep(p, 1.0 - 1.5 * tol, 1.0, 0.2, max_rate).angular_radps, 0.15);
  EXPECT_FALSE(turnStep(p, 1.0 - 1.5 * tol, 1.0, 0.2, max_rate).done);
  // Inside, not yet through the target: still the floor (the turn ends past the target, not
  // at the near edge of the band); done if the body already rests there.
  TurnStep s = turnStep(p, 1.0 - 0.5 * tol, 1.0, 0.15, max_rate);
  EXPECT_DOUBLE_EQ(s.angular_radps, 0.15);
  EXPECT_FALSE(s.done);
  EXPECT_FALSE(p.crossed);
  // Through it: zero, whatever the body still does; done only once it has settled.
  s = turnStep(p, 1.0 + 0.5 * tol, 1.0, 0.15, max_rate);
  EXPECT_TRUE(p.crossed);
  EXPECT_EQ(s.angular_radps, 0.0);
  EXPECT_FALSE(s.done);
  s = turnStep(p, 1.0 + 0.4 * tol, 1.0, -kTurnSettledRate_radps, max_rate);
  EXPECT_EQ(s.angular_radps, 0.0);
  EXPECT_FALSE(s.done);
  s = turnStep(p, 1.0 + 0.3 * tol, 1.0, 0.05, max_rate);
  EXPECT_EQ(s.angular_radps, 0.0);
  EXPECT_TRUE(s.done);
  // Overshot beyond the band: proportional, now with the lower floor (3 deg/s); re-entering
  // the band, zero at once.
  EXPECT_NEAR(turnStep(p, 1.0 + 5.0 * tol, 1.0, 0.0, max_rate).angular_radps, -3.0 * 5.0 * tol,
              1e-12);
  EXPECT_NEAR(turnStep(p, 1.0 + 1.2 * tol, 1.0, 0.0, max_rate).angular_radps, -3.0 * 1.2 * tol,
              1e-12);
  // A 0.5 deg tolerance, where the floors show at 0.8 deg: 0.15 rad/s until the target is
  // crossed, 3 deg/s after.
  const double fine = 0.5 * tol;
  TurnProgress before;
  EXPECT_DOUBLE_EQ(turnStep(before, 1.0 + 0.8 * tol, 1.0, 0.0, max_rate, fine).angular_radps,
                   -0.15);
  TurnProgress after;
  turnStep(after, 1.0 - 0.2 * tol, 1.0, 0.15, max_rate, fine);
  turnStep(after, 1.0 + 0.2 * tol, 1.0, 0.15, max_rate, fine);
  ASSERT_TRUE(after.crossed);
  EXPECT_DOUBLE_EQ(turnStep(after, 1.0 + 0.8 * tol, 1.0, 0.0, max_rate, fine).angular_radps,
                   -kTurnSettleFloor_radps);
  EXPECT_EQ(turnStep(p, 1.0 + 0.9 * tol, 1.0, -0.15, max_rate).angular_radps, 0.0);
  // A new target is a new turn.
  s = turnStep(p, 0.0, 0.5 * tol, 0.15, max_rate);
  EXPECT_FALSE(p.crossed);
  EXPECT_DOUBLE_EQ(s.angular_radps, 0.15);
  // Across the +-pi seam: the wrap is not a crossing, going through the target is.
  TurnProgress seam;
  turnStep(seam, kPi - 0.1, -kPi + 0.1, 0.5, max_rate);
  EXPECT_GT(turnStep(seam, kPi - 0.01, -kPi + 0.1, 0.5, max_rate).angular_radps, 0.0);
  EXPECT_FALSE(seam.crossed);
  turnStep(seam, -kPi + 0.1 + 0.5 * tol, -kPi + 0.1, 0.15, max_rate);
  EXPECT_TRUE(seam.crossed);
  TurnProgress half;  // a half turn: the error may wrap from +pi to -pi on the first step
  turnStep(half, 0.0, kPi, 0.0, max_rate);
  turnStep(half, -0.01, kPi, -0.5, max_rate);
  EXPECT_FALSE(half.crossed);
}

TEST(MotionTurnStep, TheFlooredRuleHuntsOverATenHertzLinkWithADelayWhereTurnStepSettles) {
  // An AmigoBot over ARCOS: SIPs every 100 ms, commands 100 ms late, 100 deg/s^2.
  const test::SampledLink link{0.1, 0.1};
  const TurnResult legacy = turnOverLink(amigo(), degToRad(90.0), /*legacy=*/true, link, 30.0);
  EXPECT_FALSE(legacy.run.finished)
      << "the floored rule settled after " << legacy.run.time_s << " s";
  EXPECT_GT(legacy.run.turn_reversals, 20);

  const TurnResult step = turnOverLink(amigo(), degToRad(90.0), /*legacy=*/false, link, 30.0);
  ASSERT_TRUE(step.run.finished);
  EXPECT_LT(step.run.time_s, 1.5 + 2.0) << "90 deg at 60 deg/s takes 1.5 s";
  EXPECT_LE(step.run.turn_reversals, 1);
  EXPECT_LT(std::abs(step.rest_error_rad), degToRad(1.5));
}

TEST(MotionTurnStep, SettlesInBoundedTimeForEveryTurnDelayAndRobot) {
  const RobotProfile robots[] = {amigo(), test::thesisRobot()};
  for (const RobotProfile& robot : robots) {
    for (const double delay_s : {0.0, 0.05, 0.1, 0.15, 0.2}) {
      for (const double turn_deg : {-180.0, -135.0, -90.0, -30.0, 15.0, 45.0, 90.0, 170.0}) {
        const double turn = degToRad(turn_deg);
        const TurnResult r = turnOverLink(robot, turn, false, {0.1, delay_s}, 30.0);
        const std::string what = robot.name + ", delay " + std::to_string(delay_s) + " s, turn " +
                                 std::to_string(turn_deg) + " deg";
        ASSERT_TRUE(r.run.finished) << what << ": " << r.run.turn_reversals << " reversals";
        // The rate-limited part, plus braking and settling on the link.
        EXPECT_LT(r.run.time_s, std::abs(turn) / kTurnRate_radps + 3.0) << what;
        EXPECT_LE(r.run.turn_reversals, 3) << what;
        EXPECT_LT(std::abs(r.rest_error_rad), degToRad(2.0)) << what;
      }
    }
  }
}

}  // namespace
}  // namespace irgs
