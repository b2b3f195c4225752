#include "core/motion/wall_follow.hpp"

#include <algorithm>
#include <cmath>

#include "core/motion/position_revision.hpp"

namespace irgs::motion {
namespace {
constexpr double kSquareWall_rad = degToRad(20.0);  // a wall ahead this close to square is across
}  // namespace

const char* wallFollowConfigProblem(const WallFollowConfig& c) {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(c.distance_m))
    return "distance_m must be > 0";
  if (!positive(c.speed_mps))
    return "speed_mps must be > 0";
  if (!positive(c.turn_rate_radps))
    return "turn_rate_radps must be > 0";
  if (!positive(c.valid_distance_m) || c.valid_distance_m <= c.distance_m)
    return "valid_distance_m must be beyond distance_m";
  if (!std::isfinite(c.turn_quantum_rad) || c.turn_quantum_rad < 0.0 ||
      c.turn_quantum_rad > degToRad(90.0))
    return "turn_quantum_rad must be in [0, 90 deg]";
  if (!positive(c.parallel_threshold_rad))
    return "parallel_threshold_rad must be > 0";
  if (!positive(c.front_margin_m) || !positive(c.lost_margin_m) || !positive(c.back_up_m))
    return "margins must be > 0";
  if (!positive(c.distance_gain_rad_per_m) || !positive(c.max_approach_rad) ||
      !positive(c.heading_gain))
    return "gains must be > 0";
  return nullptr;
}

const char* toString(WallFollowMode mode) {
  switch (mode) {
    case WallFollowMode::kSeek:
      return "seek wall";
    case WallFollowMode::kFollow:
      return "follow wall";
    case WallFollowMode::kTurn:
      return "turn";
    case WallFollowMode::kClear:
      return "clear corner";
    case WallFollowMode::kReacquire:
      return "reacquire wall";
    case WallFollowMode::kBackUp:
      return "back up";
    case WallFollowMode::kEscapeForward:
      return "escape forward";
    case WallFollowMode::kLost:
      return "lost";
  }
  return "?";
}

bool WallFollowControl::usable(const MotionGeometry& geometry, const WallFollowConfig& config) {
  return wallFollowConfigProblem(config) == nullptr &&
         findSonarRoles(geometry).canFollow(config.wall_on_left);
}

WallFollowControl::WallFollowControl(const MotionGeometry& geometry, const WallFollowConfig& config)
    : config_(config),
      view_(geometry, config.valid_distance_m),
      side_sign_(config.wall_on_left ? 1.0 : -1.0) {}

void WallFollowControl::note(WallFollowEvent event, double turn_rad) {
  event_ = event;
  event_turn_rad_ = turn_rad;
}

void WallFollowControl::restart() {
  mode_ = WallFollowMode::kSeek;
  view_.forgetBefore(now_s_);
  lost_count_ = skew_count_ = reacquire_turns_ = 0;
  have_pose_ = false;
}

bool WallFollowControl::setWallOnLeft(bool on_left) {
  if (!view_.roles().canFollow(on_left))
    return false;
  config_.wall_on_left = on_left;
  side_sign_ = on_left ? 1.0 : -1.0;
  return true;
}

bool WallFollowControl::escaping() const {
  return mode_ == WallFollowMode::kBackUp || mode_ == WallFollowMode::kTurn ||
         mode_ == WallFollowMode::kEscapeForward;
}

void WallFollowControl::startStraight(WallFollowMode mode, const Pose2& pose) {
  mode_ = mode;
  leg_start_ = pose.position();
  hold_heading_ = pose.theta;
}

VelocityCommand WallFollowControl::escapeBlocked(const Pose2& pose) {
  const EscapeMove move = escape_.next(mode_ == WallFollowMode::kTurn);
  ++bumps_;
  switch (move) {
    case EscapeMove::kBackUp:
      startStraight(WallFollowMode::kBackUp, pose);
      note(WallFollowEvent::kBlockedBackUp);
      return {-0.5 * config_.speed_mps, 0.0};
    case EscapeMove::kTurn:
      note(WallFollowEvent::kBlockedTurnAway);
      return startTurn(-side_sign_ * kEscapeTurn_rad, WallFollowMode::kReacquire, pose);
    case EscapeMove::kForward:
      startStraight(WallFollowMode::kEscapeForward, pose);
      note(WallFollowEvent::kBlockedCreep);
      return {0.5 * config_.speed_mps, 0.0};
    case EscapeMove::kTurnOpposite:
      break;
  }
  note(WallFollowEvent::kBlockedTurnToward);
  return startTurn(side_sign_ * kEscapeTurn_rad, WallFollowMode::kReacquire, pose);
}

VelocityCommand WallFollowControl::startTurn(double turn_rad, WallFollowMode next,
                                             const Pose2& pose) {
  target_heading_ = wrapAngle(pose.theta + turn_rad);
  next_mode_ = next;
  mode_ = WallFollowMode::kTurn;
  ++turns_;
  turn_progress_ = {};
  return {0.0, turnStep(turn_progress_, pose.theta, target_heading_, measured_rate_radps_,
                        config_.turn_rate_radps)
                   .angular_radps};
}

// (a) A wall ahead: turn by the front pair's right-triangle angle so the wall ends up on the
// followed side, or by a quarter turn when the pair cannot see it.
VelocityCommand WallFollowControl::handleWallAhead(const Pose2& pose) {
  const SonarRoles& r = view_.roles();
  std::optional<double> turn;
  const auto dl = view_.range(r.front_left), dr = view_.range(r.front_right);
  if (dl && dr)
    turn =
        frontWallTurn(*dl, *dr, r.front_baseline_m, config_.wall_on_left, config_.turn_quantum_rad);
  double t = turn ? *turn : -side_sign_ * 0.5 * kPi;
  // Never turn toward the wall side and never more than 135 degrees at once.
  if (t * side_sign_ > 0.0)
    t = -side_sign_ * 0.5 * kPi;
  t = std::clamp(t, -degToRad(135.0), degToRad(135.0));
  ++corner_turns_;
  note(WallFollowEvent::kWallAhead, t);
  return startTurn(t, WallFollowMode::kFollow, pose);
}

// While clearing a convex corner: a surface straight across the way, with the body already past
// the corner, is the far side of a passage (an obstacle near a wall), not the next face of the
// followed one (met at a slant). Turning round the corner keeps the traced surface; turning
// away would trace the other one instead.
bool WallFollowControl::passageAhead(const Pose2& pose) const {
  const SonarRoles& r = view_.roles();
  const auto dl = view_.range(r.front_left), dr = view_.range(r.front_right);
  const auto skew = dl && dr ? frontWallSkew(*dl, *dr, r.front_baseline_m) : std::nullopt;
  if (!skew || std::abs(*skew) > kSquareWall_rad)
    return false;
  const double past_corner =
      (pose.position() - leg_start_).norm() - (leg_length_m_ - config_.distance_m);
  return past_corner >= view_.geometry().body_radius_m;
}

std::optional<double> WallFollowControl::sideWallDistance() const {
  const SonarRoles::SidePair& pair = view_.roles().side(config_.wall_on_left);
  const auto df = view_.sideDistance(pair.front);
  if (df && *df <= config_.distance_m + config_.lost_margin_m)
    return df;
  return std::nullopt;
}

VelocityCommand WallFollowControl::follow(const Pose2& pose) {
  const SonarRoles::SidePair& pair = view_.roles().side(config_.wall_on_left);
  const double present_limit = config_.distance_m + config_.lost_margin_m;
  auto df = view_.sideDistance(pair.front);
  auto dr = view_.sideDistance(pair.rear);
  if (df && *df > present_limit)
    df.reset();
  if (dr && *dr > present_limit)
    dr.reset();

  if (!df) {
    // (b) The wall ended ahead of the front side sonar: a convex corner (or a doorway). Two
    // missing readings in a row, so a single dropout does not start a corner.
    if (view_.updatedNow(pair.front))
      ++lost_count_;
    if (lost_count_ >= 2) {
      lost_count_ = 0;
      const SonarMount& spec = view_.geometry().sonars[static_cast<std::size_t>(pair.front)];
      const double side_range = std::max(0.0, last_side_m_ - std::abs(spec.mount.y));
      leg_length_m_ =
          cornerClearance(spec.mount.x, side_range, spec.half_beam_rad, config_.distance_m);
      leg_start_ = pose.position();
      hold_heading_ = pose.theta;
      mode_ = WallFollowMode::kClear;
      note(WallFollowEvent::kCornerClear);
      return straightCommand(pose.theta, hold_heading_, config_.speed_mps);
    }
    follow_heading_ = pose.theta;
    return straightCommand(pose.theta, pose.theta, config_.speed_mps);
  }
  lost_count_ = 0;
  reacquire_turns_ = 0;

  double wall_angle = 0.0;
  double distance = *df;
  if (dr) {
    wall_angle = sideWallAngle(*df, *dr, pair.baseline_m, config_.wall_on_left).value_or(0.0);
    wall_angle_ = wall_angle;
    distance = 0.5 * (*df + *dr) * std::cos(wall_angle);
    // (c) Off parallel by the threshold or more on two fresh readings: stop and turn back.
    if (view_.updatedNow(pair.front) || view_.updatedNow(pair.rear)) {
      if (std::abs(wall_angle) >= config_.parallel_threshold_rad)
        ++skew_count_;
      else
        skew_count_ = 0;
    }
    if (skew_count_ >= 2) {
      skew_count_ = 0;
      if (const auto turn = parallelCorrection(wall_angle, config_.parallel_threshold_rad,
                                               config_.turn_quantum_rad)) {
        ++corrections_;
        note(WallFollowEvent::kRestoreParallel, *turn);
        return startTurn(*turn, WallFollowMode::kFollow, pose);
      }
    }
  }
  last_side_m_ = *df;
  // (d) Steer back toward the set distance, never steeper than max_approach_rad.
  const double offset =
      distanceKeepingOffset(distance, config_.distance_m, config_.valid_distance_m,
                            config_.distance_gain_rad_per_m, config_.max_approach_rad);
  const double heading_error = wall_angle + side_sign_ * offset;
  follow_heading_ = wrapAngle(pose.theta + heading_error);
  const double w = std::clamp(config_.heading_gain * heading_error, -config_.turn_rate_radps,
                              config_.turn_rate_radps);
  const double v = config_.speed_mps * std::max(0.3, 1.0 - std::abs(heading_error));
  return {v, w};
}

VelocityCommand WallFollowControl::step(const MotionInput& input) {
  event_ = WallFollowEvent::kNone;
  now_s_ = input.time_s;
  measured_rate_radps_ = input.measured.angular_radps;
  wall_angle_.reset();
  view_.update(input);
  const Pose2& pose = input.odometry;
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    note(WallFollowEvent::kPoseNotFinite);
    heading_setpoint_.reset();
    return {};
  }
  if (have_pose_)
    distance_m_ += (pose.position() - last_pose_.position()).norm();
  last_pose_ = pose;
  have_pose_ = true;

  if (input.inContact() && !escaping()) {
    ++bumps_;
    startStraight(WallFollowMode::kBackUp, pose);
    note(WallFollowEvent::kBumper);
  }
  // A turn or a straight escape that is blocked would wait forever for progress that cannot
  // come (a bumper hit above has just started a back-up: that counts).
  if (!input.inContact() || !escaping()) {
    contact_since_s_.reset();
  } else if (!contact_since_s_) {
    contact_since_s_ = input.time_s;
  } else if (input.time_s - *contact_since_s_ >= config_.blocked_s) {
    contact_since_s_.reset();
    const VelocityCommand command = escapeBlocked(pose);
    heading_setpoint_ = setpointFor(command, pose);
    return command;
  }
  const VelocityCommand command = modeStep(input, pose);
  heading_setpoint_ = setpointFor(command, pose);
  return command;
}

std::optional<double> WallFollowControl::setpointFor(const VelocityCommand& command,
                                                     const Pose2& pose) const {
  if (command == VelocityCommand{})
    return std::nullopt;
  switch (mode_) {
    case WallFollowMode::kTurn:
      return target_heading_;
    case WallFollowMode::kFollow:
      return follow_heading_;
    case WallFollowMode::kSeek:
    case WallFollowMode::kLost:
      return pose.theta;
    case WallFollowMode::kClear:
    case WallFollowMode::kReacquire:
    case WallFollowMode::kBackUp:
    case WallFollowMode::kEscapeForward:
      return hold_heading_;
  }
  return std::nullopt;
}

VelocityCommand WallFollowControl::modeStep(const MotionInput& input, const Pose2& pose) {
  const auto front = view_.frontDistance();
  const bool wall_ahead = front && *front < config_.distance_m + config_.front_margin_m;

  switch (mode_) {
    case WallFollowMode::kTurn:
      if (const TurnStep turn = turnStep(turn_progress_, pose.theta, target_heading_,
                                         measured_rate_radps_, config_.turn_rate_radps);
          !turn.done) {
        return {0.0, turn.angular_radps};
      }
      mode_ = next_mode_;
      escape_.reset();                   // a completed turn: the body is free again
      view_.forgetBefore(input.time_s);  // readings taken while turning look elsewhere
      leg_start_ = pose.position();
      hold_heading_ = pose.theta;
      return {};
    case WallFollowMode::kBackUp:
      if ((pose.position() - leg_start_).norm() >= config_.back_up_m)
        return startTurn(-side_sign_ * kEscapeTurn_rad, WallFollowMode::kReacquire, pose);
      return {-0.5 * config_.speed_mps, 0.0};
    case WallFollowMode::kEscapeForward:
      // Whatever wedged the body is behind it now: look for the wall again from here.
      if ((pose.position() - leg_start_).norm() >= config_.back_up_m) {
        startStraight(WallFollowMode::kReacquire, pose);
        return straightCommand(pose.theta, hold_heading_, config_.speed_mps);
      }
      return {0.5 * config_.speed_mps, 0.0};
    case WallFollowMode::kSeek:
    case WallFollowMode::kLost:
      if (wall_ahead)
        return handleWallAhead(pose);
      if (sideWallDistance()) {
        mode_ = WallFollowMode::kFollow;
        return follow(pose);
      }
      return straightCommand(pose.theta, pose.theta, config_.speed_mps);
    case WallFollowMode::kClear:
      if (wall_ahead && !passageAhead(pose))
        return handleWallAhead(pose);
      if (wall_ahead || (pose.position() - leg_start_).norm() >= leg_length_m_) {
        ++corner_turns_;
        note(WallFollowEvent::kCornerTurn, side_sign_ * 0.5 * kPi);
        return startTurn(side_sign_ * 0.5 * kPi, WallFollowMode::kReacquire, pose);
      }
      return straightCommand(pose.theta, hold_heading_, config_.speed_mps);
    case WallFollowMode::kReacquire:
      if (wall_ahead)
        return handleWallAhead(pose);
      if (sideWallDistance()) {
        mode_ = WallFollowMode::kFollow;
        return follow(pose);
      }
      if ((pose.position() - leg_start_).norm() >= 2.0 * config_.distance_m + 0.05) {
        if (++reacquire_turns_ >= 4) {
          reacquire_turns_ = 0;
          mode_ = WallFollowMode::kLost;
          note(WallFollowEvent::kLost);
          return {};
        }
        return startTurn(side_sign_ * 0.5 * kPi, WallFollowMode::kReacquire, pose);
      }
      return straightCommand(pose.theta, hold_heading_, config_.speed_mps);
    case WallFollowMode::kFollow:
      if (wall_ahead)
        return handleWallAhead(pose);
      return follow(pose);
  }
  return {};
}

}  // namespace irgs::motion
