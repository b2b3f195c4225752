#pragma once
// The traveling algorithm executed on the robot's telemetry (003_… section 4.3, Figs. 4.8-4.10;
// digest 4.10): for each TravelSegment the robot stops, turns on the spot to the segment's
// quantised heading, then drives to the next turning point holding its heading, and reports
// arrival there. After the last segment it stops.
//
// Control (per sample, from the odometry pose, so it works the same on a linked robot):
// * turn: omega = sign(e) * min(max_turn_rate, sqrt(2 * turn_accel * |e|) * kBrakeMargin,
//   turn_gain * |e|) with a floor of min_turn_rate while |e| > heading_tolerance: the square
//   root brakes in time for the profile's angular acceleration, so the turn does not overshoot.
// * drive: v from the remaining distance d along the segment the same way (max_speed,
//   sqrt(2 * accel * d), floor min_speed); omega = heading_gain * wrap(aim - theta) where aim
//   points at the turning point (steer_to_turning_points, the default) or is the quantised
//   heading (the thesis robot's open-loop distance). The drive ends when d <= arrival_tolerance.
// * safety: with a robot profile and stop_distance_m > 0, a forward sonar echo closer than
//   stop_distance_m that also lies before the turning point (closer than the remaining distance
//   plus the body's front extent) ends the run as failed: the map was wrong there.
// * watchdog: a phase that makes no progress (heading error or remaining distance not shrinking
//   by kProgressStep) for stall_timeout_s of robot time, or a pressed bumper while driving,
//   finishes the behaviour as failed with the reason in status().message.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/behaviour/behaviour.hpp"
#include "core/behaviour/sonar_view.hpp"
#include "core/planning/traveling.hpp"
#include "core/robot/robot_profile.hpp"

namespace irgs {

struct TravelOptions {
  double max_speed_mps = 0.25;
  double min_speed_mps = 0.02;  // floor near the end of a leg, so the robot arrives
  double accel_mps2 = 0.5;      // braking assumed for the approach (profile's max_accel)
  double max_turn_rate_radps = degToRad(60.0);
  double min_turn_rate_radps = degToRad(4.0);
  double turn_accel_radps2 = degToRad(180.0);
  double turn_gain = 3.0;     // 1/s, proportional turn rate near the target heading
  double heading_gain = 2.5;  // 1/s, heading hold while driving
  double heading_tolerance_rad = degToRad(1.0);
  double arrival_tolerance_m = 0.01;
  bool steer_to_turning_points = true;
  bool stop_on_bumper = true;
  double stall_timeout_s = 4.0;  // robot time without progress before giving up
  // Forward-sonar safety stop (needs the profile constructor), metres from the body origin;
  // 0 switches it off.
  double stop_distance_m = 0.0;
};

// Options limited by the profile's speeds and accelerations (the defaults otherwise).
TravelOptions travelOptionsFor(const RobotProfile& profile);

// What is wrong with the options (non-finite, non-positive limits, min > max, ...), or nothing.
std::optional<std::string> travelOptionsError(const TravelOptions& options);

// The short form irgs-sim uses: cruise speed, turn rate and the forward-sonar stop distance.
struct TravelConfig {
  double speed_mps = 0.2;
  double turn_rate_radps = degToRad(60.0);
  // Stop when a forward sonar sees something closer than this to the body origin.
  double stop_distance_m = 0.25;
};

class TravelBehaviour : public Behaviour {
 public:
  enum class Phase { kTurn, kDrive, kDone };

  // Throws std::invalid_argument for invalid options or a plan with non-finite values.
  // An empty plan finishes at once (successfully). No sonar safety stop.
  explicit TravelBehaviour(TravelPlan plan, TravelOptions options = {});
  // With the robot's sonars: options.stop_distance_m > 0 enables the forward-sonar stop.
  TravelBehaviour(const RobotProfile& profile, TravelPlan plan, const TravelOptions& options);
  // travelOptionsFor(profile) with config's speed, turn rate and stop distance. Throws
  // std::invalid_argument for non-positive speeds or a negative stop distance.
  TravelBehaviour(const RobotProfile& profile, TravelPlan plan, TravelConfig config = {});

  VelocityCommand onSample(const TelemetrySample& sample) override;
  BehaviourStatus status() const override;
  std::string_view name() const override { return "travel"; }

  const TravelPlan& plan() const { return plan_; }
  Phase phase() const { return phase_; }
  // Index of the segment being executed (segments().size() when done).
  std::size_t segmentIndex() const { return segment_; }
  std::size_t segmentsDone() const { return arrivals_.size(); }
  // Turning points reached so far (the end of each finished segment), in order.
  const std::vector<Vec2>& arrivals() const { return arrivals_; }
  // Odometry positions at those arrivals (where the robot believed it was).
  const std::vector<Vec2>& arrivalPoses() const { return arrival_positions_; }

 private:
  VelocityCommand turnCommand(const Pose2& pose, double time_s);
  VelocityCommand driveCommand(const TelemetrySample& sample);
  void startSegment(std::size_t index, double time_s);
  void finish(bool failed, std::string message);
  void noteProgress(double measure, double time_s);
  bool stalled(double time_s) const;
  void validate();

  TravelPlan plan_;
  TravelOptions options_;
  std::optional<SonarView> sonar_;  // forward-sonar stop, with a profile
  double front_extent_m_ = 0.0;     // body outline ahead of the origin
  Phase phase_ = Phase::kTurn;
  std::size_t segment_ = 0;
  bool failed_ = false;
  std::string message_;
  std::string phase_text_;
  std::vector<Vec2> arrivals_;
  std::vector<Vec2> arrival_positions_;
  double done_distance_m_ = 0.0;  // distance of finished segments
  double leg_progress_m_ = 0.0;   // distance made on the current leg
  // Watchdog: the best value of the phase's progress measure and when it last improved.
  std::optional<double> best_measure_;
  double improved_at_s_ = 0.0;
  bool started_ = false;
};

std::string_view toString(TravelBehaviour::Phase phase);

}  // namespace irgs
