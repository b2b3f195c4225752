#include "core/mission/map_building_mission.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/geometry/geometry_queries.hpp"
#include "core/motion/host_adapters.hpp"
#include "core/motion/position_revision.hpp"

namespace irgs {
namespace {

constexpr double kApproachLimit_m = 0.8;  // drive at most this far toward a suspected obstacle
constexpr double kApproachSpeed_mps = 0.15;
constexpr double kScanRate_radps = 0.8;
constexpr double kEscapeDistance_m = 0.1;  // back up or creep forward this far
constexpr double kEscapeSpeed_mps = 0.1;
constexpr double kLoopPause_s = 1.0;  // rest after a loop closed
// Around the point where an obstacle loop started, no new obstacle target after the loop closed.
constexpr double kAnchorBlacklist_m = 0.5;
constexpr double kMissedAnchorBlacklist_m = 1.2;
constexpr double kPocketMaxArea_m2 = 1.0;  // clockwise obstacle loops smaller than this: pockets
constexpr int kMaxSafetyRetries = 5;       // a primitive stopped by the robot's safety rules

std::string formatPoint(const Vec2& p) {
  char text[48];
  std::snprintf(text, sizeof text, "(%.2f, %.2f)", p.x(), p.y());
  return text;
}

MapBuildingConfig checked(MapBuildingConfig c) {
  if (const auto err = mapBuildingConfigError(c))
    throw std::invalid_argument("MapBuildingConfig: " + *err);
  c.follow.wall_on_left = true;
  c.follow.turn_quantum_rad = c.turn_quantum_rad;
  return c;
}

// The long-range knowledge grid: echoes clear the cone up to the explore range, no echo clears
// as far.
SonarInverseModel exploreModel(const MapBuildingConfig& c) {
  SonarInverseModel m = c.sonar_model;
  m.no_echo_free_range_m = std::max(m.no_echo_free_range_m, c.explore_range_m);
  return m;
}

const RobotProfile& followable(const RobotProfile& profile) {
  if (!motion::findSonarRoles(motion::motionGeometryOf(profile)).canFollow(true))
    throw std::invalid_argument("robot profile '" + profile.name +
                                "' has no forward sonar and left side sonar to follow walls");
  return profile;
}

}  // namespace

MapBuildingMission::MapBuildingMission(const RobotProfile& profile, MapBuildingConfig config)
    : config_(checked(config)),
      profile_(followable(profile)),
      geometry_(motion::motionGeometryOf(profile)),
      sonar_(geometry_, config_.map_valid_distance_m),
      revised_(profile, config_),
      mapper_(profile, config_.sonar_model, config_.map_valid_distance_m),
      grid_(config_.grid_resolution_m),
      explore_mapper_(profile, exploreModel(config_),
                      config_.explore_range_m > 0.0 ? config_.explore_range_m : 1.0),
      explore_grid_(0.5 * config_.explore_cell_m),
      record_(config_.follow.distance_m + 0.3),
      loops_(config_.index_spacing_m, config_.closure_radius_m, config_.min_loop_length_m),
      body_radius_m_(profile.bodyRadius()) {}

// ---- requests -----------------------------------------------------------------------------------

void MapBuildingMission::send(const motion::PrimitiveSpec& spec, Move move) {
  active_id_ = next_id_++;
  request_ = StartPrimitive{{active_id_, spec}};
  move_ = move;
  last_spec_ = spec;
  if (move == Move::kFollow)
    follower_mode_ = static_cast<int>(motion::WallFollowMode::kSeek);
}

void MapBuildingMission::cancelPrimitive() {
  request_ = CancelPrimitive{};
  active_id_ = 0;
  move_ = Move::kNone;
}

std::optional<MissionRequest> MapBuildingMission::takeRequest() {
  return std::exchange(request_, std::nullopt);
}

void MapBuildingMission::fail(const std::string& why) {
  phase_ = MapBuildingPhase::kFailed;
  message_ = why;
  cancelPrimitive();
}

bool MapBuildingMission::following() const {
  return move_ == Move::kFollow &&
         follower_mode_ == static_cast<int>(motion::WallFollowMode::kFollow);
}

Vec2 MapBuildingMission::toOdometry(const Vec2& map_point) const {
  return revised_.odometryOf({map_point.x(), map_point.y(), 0.0}).position();
}

void MapBuildingMission::turnTo(double map_heading_rad, Move move) {
  const Pose2& p = pose();
  motion::TurnSpec turn;
  turn.angle_rad = revised_.odometryOf({p.x, p.y, map_heading_rad}).theta;
  turn.absolute = true;
  turn.rate_radps = config_.follow.turn_rate_radps;
  send(turn, move);
}

void MapBuildingMission::startFollowing(MapBuildingPhase phase) {
  ++follow_epoch_;
  phase_ = phase;
  loops_.restart();
  loop_interior_m_ = 0.0;
  motion::FollowWallSpec follow;
  follow.wall_on_left = true;
  follow.distance_m = config_.follow.distance_m;
  follow.speed_mps = config_.follow.speed_mps;
  send(follow, Move::kFollow);
}

// ---- telemetry ----------------------------------------------------------------------------------

void MapBuildingMission::onSample(const TelemetrySample& raw) {
  now_s_ = raw.time_s;
  if (phase_ == MapBuildingPhase::kDone || phase_ == MapBuildingPhase::kFailed)
    return;
  const Pose2& odo = raw.odometry_pose;
  if (!std::isfinite(odo.x) || !std::isfinite(odo.y) || !std::isfinite(odo.theta))
    return fail("odometry pose is not finite");
  revised_.onOdometry(odo);
  if (started_ && record_.outline() && config_.wall_ranging)
    revised_.rangeToRoomWalls(raw, grid_);
  TelemetrySample sample = raw;
  sample.odometry_pose = pose();
  const Pose2 at = pose();  // before this sample's wall fit revises it
  sonar_.update(motion::motionInputOf(sample));
  mapper_.integrate(sample, grid_);
  if (config_.explore_range_m > 0.0)
    explore_mapper_.integrate(sample, explore_grid_);
  if (!started_) {
    started_ = true;
    start_time_s_ = sample.time_s;
    last_pose_ = at;
    scan_start_heading_ = at.theta;
    motion::TurnSpec scan;
    scan.angle_rad = 2.0 * kPi;  // counter-clockwise, all round
    scan.rate_radps = std::min(kScanRate_radps, config_.follow.turn_rate_radps);
    send(scan, Move::kScan);
  }
  distance_m_ += (at.position() - last_pose_.position()).norm();
  if (phase_ == MapBuildingPhase::kScan) {
    scan_turned_rad_ += std::abs(wrapAngle(at.theta - last_pose_.theta));
    scanSample();
  }
  if (sample.time_s - start_time_s_ > config_.max_time_s) {
    fail("time budget of " + std::to_string(static_cast<int>(config_.max_time_s)) +
         " s used up in phase '" + std::string(toString(phase_)) + "'");
  } else if (distance_m_ > config_.max_distance_m) {
    fail("distance budget of " + std::to_string(static_cast<int>(config_.max_distance_m)) +
         " m used up in phase '" + std::string(toString(phase_)) + "'");
  } else if (move_ == Move::kFollow) {
    trackFollow(sample);
  } else if (move_ == Move::kPause && sample.time_s >= pause_until_s_) {
    afterPause();
  }
  last_pose_ = at;
}

void MapBuildingMission::scanSample() {
  // The nearest echo ahead in every direction of the scan turn.
  const auto front = sonar_.frontDistance();
  if (!front)
    return;
  if (scan_initial_range_ < 0.0 && scan_turned_rad_ < degToRad(10.0))
    scan_initial_range_ = *front;
  if (scan_best_range_ == 0.0 || *front < scan_best_range_) {
    scan_best_range_ = *front;
    scan_best_heading_ = pose().theta;
  }
}

void MapBuildingMission::afterScan() {
  // Prefer the initial heading unless another wall is clearly nearer (each turn adds error).
  double heading = scan_start_heading_;
  if (scan_best_range_ > 0.0 &&
      (scan_initial_range_ < 0.0 || scan_initial_range_ > 1.25 * scan_best_range_ + 0.1))
    heading =
        scan_start_heading_ + quantiseAngle(wrapAngle(scan_best_heading_ - scan_start_heading_),
                                            config_.turn_quantum_rad);
  phase_ = MapBuildingPhase::kSeekWall;
  message_ = "scan done: heading for the nearest wall";
  turnTo(wrapAngle(heading), Move::kSeekTurn);
}

void MapBuildingMission::trackFollow(const TelemetrySample& sample) {
  const Pose2 at = sample.odometry_pose;
  revised_.fitWall(sample, {following(), phase_ == MapBuildingPhase::kObstacle,
                            phase_ == MapBuildingPhase::kFollowWall && !record_.outline(),
                            follow_epoch_, distance_m_});
  const std::optional<std::size_t> closed = loops_.onPose(at, following());
  if (loops_.started() && phase_ == MapBuildingPhase::kSeekWall)
    phase_ = MapBuildingPhase::kFollowWall;
  // An obstacle loop that goes on and on has merged several obstacles packed closer than the
  // follower's reach (or keeps missing its start): what it passed is mapped and explained;
  // give it up and go on with the interior.
  if (phase_ == MapBuildingPhase::kObstacle &&
      !record_.nearOutline(at.position(), config_.follow.distance_m + 0.3) && record_.outline())
    loop_interior_m_ += (at.position() - last_pose_.position()).norm();
  if (phase_ == MapBuildingPhase::kObstacle && loop_interior_m_ > config_.max_obstacle_loop_m)
    return giveUpObstacleLoop();
  if (closed)
    onLoopClosed(*closed);
}

// ---- loops --------------------------------------------------------------------------------------

void MapBuildingMission::giveUpObstacleLoop() {
  TracedLoop partial;
  partial.indices = loops_.indices();
  record_.addPocket(partial);
  if (obstacle_anchor_) {
    record_.blacklist(*obstacle_anchor_, kMissedAnchorBlacklist_m);
    record_.addObstacleAnchor(*obstacle_anchor_);
    obstacle_anchor_.reset();
  }
  loops_.restart();
  ++follow_epoch_;
  message_ = "obstacle loop given up after " +
             std::to_string(static_cast<int>(config_.max_obstacle_loop_m)) + " m";
  phase_ = MapBuildingPhase::kLoopClosed;
  after_pause_ = MapBuildingPhase::kInterior;
  cancelPrimitive();
  move_ = Move::kPause;
  pause_until_s_ = now_s_ + kLoopPause_s;
}

void MapBuildingMission::onLoopClosed(std::size_t from_index) {
  const TracedLoop loop = loops_.loopFrom(from_index, pose().position());
  const bool was_outline_search = phase_ == MapBuildingPhase::kFollowWall;
  const bool was_obstacle = phase_ == MapBuildingPhase::kObstacle;
  ++follow_epoch_;
  phase_ = MapBuildingPhase::kLoopClosed;
  cancelPrimitive();
  move_ = Move::kPause;
  pause_until_s_ = now_s_ + kLoopPause_s;
  if (was_obstacle && obstacle_anchor_) {
    // Whatever the loop looked like, the surface that started it has been followed: never
    // start again from there (a concave pocket of an obstacle closes small clockwise loops).
    // A loop that did not enclose it went round a neighbour instead (obstacles closer than
    // the follower's reach): that surface was seen from close by, so leave its whole
    // neighbourhood to the map rather than trying again from its other faces.
    const bool missed = loop.obstacle && !pointInPolygon(*obstacle_anchor_, loop.indices);
    record_.blacklist(*obstacle_anchor_, missed ? kMissedAnchorBlacklist_m : kAnchorBlacklist_m);
    record_.addObstacleAnchor(*obstacle_anchor_);
    obstacle_anchor_.reset();
  }
  if (was_obstacle && !loop.obstacle && record_.outline()) {
    // Clockwise inside the room: a small one is a pocket of the obstacle being followed (its
    // surroundings are explained); a large one went round the room along its walls and
    // explains nothing new.
    if (-loop.signed_area_m2 < kPocketMaxArea_m2) {
      record_.addPocket(loop);
      message_ = "obstacle pocket traced (" + std::to_string(loop.indices.size()) + " indices)";
    } else {
      message_ = "obstacle loop went round the room";
    }
    after_pause_ = MapBuildingPhase::kInterior;
  } else if (loop.obstacle) {
    record_.addObstacle(loop);
    const auto count = std::to_string(record_.obstacles().size());
    if (was_outline_search && !record_.outline()) {
      first_wall_was_obstacle_ = record_.obstacles().size() == 1 || first_wall_was_obstacle_;
      message_ = "loop closed counter-clockwise: the first wall was obstacle " + count +
                 "; going on to the real wall";
      after_pause_ = MapBuildingPhase::kSeekWall;
    } else {
      message_ = "obstacle " + count + " circumnavigated";
      after_pause_ = record_.outline() ? MapBuildingPhase::kInterior : MapBuildingPhase::kSeekWall;
    }
  } else {
    if (!record_.outline())
      record_.setOutline(loop);
    message_ = "outline loop closed (" + std::to_string(loop.indices.size()) + " indices, " +
               std::to_string(static_cast<int>(std::lround(-loop.signed_area_m2))) + " m2)";
    after_pause_ = MapBuildingPhase::kInterior;
  }
  loops_.restart();
}

void MapBuildingMission::afterPause() {
  move_ = Move::kNone;
  if (after_pause_ == MapBuildingPhase::kSeekWall) {
    // Turn away from the obstacle just traced (it is on the left) and seek the wall.
    phase_ = MapBuildingPhase::kSeekWall;
    turnTo(wrapAngle(pose().theta - 0.5 * kPi), Move::kSeekTurn);
    return;
  }
  phase_ = after_pause_;
  nextInteriorTarget();
}

// ---- interior -----------------------------------------------------------------------------------

void MapBuildingMission::nextInteriorTarget() {
  InteriorSearchConfig search;
  search.cell_m = config_.explore_cell_m;
  search.explore_range_m = config_.explore_range_m;
  search.inflate_m = body_radius_m_ + config_.clearance_margin_m;
  search.beyond_outline = config_.explore_beyond_outline;
  target_ = chooseInteriorTarget(pose(), grid_, explore_grid_, record_, search);
  if (!target_) {
    phase_ = MapBuildingPhase::kDone;
    message_ = "map complete: outline closed, " + std::to_string(obstacleCount()) +
               " obstacle(s), no reachable unknown area left";
    cancelPrimitive();
    return;
  }
  if (target_->path.size() < 2)
    return arrived();  // already there
  motion::SegmentsSpec travel;
  travel.speed_mps = config_.travel_speed_mps;
  travel.clearance_m = config_.follow.distance_m + config_.follow.front_margin_m;
  travel.stop_beyond_waypoint = true;  // a wall met on the way may be an unvisited obstacle
  for (std::size_t i = 1; i < target_->path.size() && travel.append(toOdometry(target_->path[i]));
       ++i) {
  }
  // A path with more turning points than one primitive carries ends early at its last one:
  // arrival is then checked again from there.
  send(travel, Move::kTravel);
}

void MapBuildingMission::arrived() {
  if ((pose().position() - target_->position).norm() > config_.explore_cell_m &&
      target_->path.size() > motion::kMaxWaypoints) {
    nextInteriorTarget();  // the rest of a long path: plan again from here
    return;
  }
  ++targets_visited_;
  if (target_->obstacle) {
    const Vec2 d = target_->obstacle_point - pose().position();
    turnTo(std::atan2(d.y(), d.x()), Move::kFaceObstacle);
    return;
  }
  record_.blacklist(target_->position, 0.4);
  nextInteriorTarget();
}

void MapBuildingMission::frontWall() {
  const double front =
      sonar_.frontDistance().value_or(config_.follow.distance_m + config_.follow.front_margin_m);
  const Vec2 hit = pose().position() + front * pose().heading();
  if (move_ == Move::kApproach) {
    message_ = "obstacle reached at " + formatPoint(hit) + ": circumnavigate counter-clockwise";
    obstacle_anchor_ = hit;
    return startFollowing(MapBuildingPhase::kObstacle);
  }
  if (record_.insideOutline(hit) && !record_.explained(hit) && !record_.visitedOften(hit)) {
    message_ = "obstacle met at " + formatPoint(hit) + ": circumnavigate counter-clockwise";
    obstacle_anchor_ = hit;
    return startFollowing(MapBuildingPhase::kObstacle);
  }
  record_.blacklist(target_->position, 0.3);
  nextInteriorTarget();
}

// A move that is blocked — in contact for the blocked time, the wheels stalled — would wait for
// ever for progress that cannot come: the escape ladder picks the next move to try, and after
// it the mission goes on from where the body got free.
void MapBuildingMission::escape(bool blocked_move_was_turn) {
  motion::DriveSpec drive;
  drive.speed_mps = kEscapeSpeed_mps;
  drive.stop_at_wall = false;
  motion::TurnSpec turn;
  turn.rate_radps = config_.follow.turn_rate_radps;
  switch (escape_.next(blocked_move_was_turn)) {
    case EscapeMove::kBackUp:
      drive.distance_m = -kEscapeDistance_m;
      return send(drive, Move::kBackUp);
    case EscapeMove::kForward:
      drive.distance_m = kEscapeDistance_m;
      return send(drive, Move::kCreep);
    case EscapeMove::kTurn:
      turn.angle_rad = -kEscapeTurn_rad;
      return send(turn, Move::kEscapeTurn);
    case EscapeMove::kTurnOpposite:
      turn.angle_rad = kEscapeTurn_rad;
      return send(turn, Move::kEscapeTurn);
  }
}

// After an escape move: on with what the phase was doing.
void MapBuildingMission::resume() {
  if (phase_ == MapBuildingPhase::kSeekWall)
    return startFollowing(MapBuildingPhase::kSeekWall);
  nextInteriorTarget();
}

// ---- reports ------------------------------------------------------------------------------------

void MapBuildingMission::onReport(const motion::MotionReport& report) {
  if (report.id != active_id_ || active_id_ == 0 || phase_ == MapBuildingPhase::kDone ||
      phase_ == MapBuildingPhase::kFailed)
    return;
  if (report.kind == motion::ReportKind::kMode) {
    follower_mode_ = report.index;
    return;
  }
  if (!motion::isFinal(report.kind))
    return;
  active_id_ = 0;
  onFinal(report);
}

void MapBuildingMission::onFinal(const motion::MotionReport& report) {
  using motion::Reason;
  using motion::ReportKind;
  const Move move = move_;
  move_ = Move::kNone;
  if (report.kind == ReportKind::kRefused)
    return fail(std::string("the robot refused ") + motion::toString(motion::kindOf(last_spec_)) +
                ": " + motion::toString(report.reason));
  if (report.kind == ReportKind::kCancelled)
    return fail(std::string("the robot cancelled ") + motion::toString(motion::kindOf(last_spec_)));
  if (report.kind == ReportKind::kFailed && report.reason == Reason::kSafety) {
    // The robot stopped on its own (the link went quiet, an e-stop released since): the same
    // move again, a few times.
    if (++safety_retries_ > kMaxSafetyRetries)
      return fail("the robot's safety stops ended the run");
    return send(last_spec_, move);
  }
  const bool done = report.kind == ReportKind::kDone;
  const bool bumped = report.kind == ReportKind::kFailed && report.reason == Reason::kBumped;
  switch (move) {
    case Move::kScan:
      return afterScan();  // a scan cut short still chose from what it saw
    case Move::kSeekTurn:
    case Move::kFaceObstacle:
      if (!done)
        return escape(true);
      escape_.reset();  // a turn of the plan completed: the body is free again
      if (move == Move::kSeekTurn)
        return startFollowing(MapBuildingPhase::kSeekWall);
      {
        motion::DriveSpec approach;
        approach.distance_m = kApproachLimit_m;
        approach.speed_mps = kApproachSpeed_mps;
        approach.clearance_m = config_.follow.distance_m + config_.follow.front_margin_m;
        return send(approach, Move::kApproach);
      }
    case Move::kFollow:
      return fail(std::string("wall following ended on the robot: ") +
                  motion::toString(report.kind) + " " + motion::toString(report.reason));
    case Move::kTravel:
    case Move::kApproach:
      if (report.kind == ReportKind::kFrontWall)
        return frontWall();
      if (done && move == Move::kTravel)
        return arrived();
      if (done) {  // the approach found nothing within reach
        record_.blacklist(target_->obstacle_point, 0.3);
        return nextInteriorTarget();
      }
      // Contact on the way, or stuck: back off and leave that target.
      if (target_)
        record_.blacklist(target_->position, 0.3);
      if (bumped) {
        motion::DriveSpec back;
        back.distance_m = -kEscapeDistance_m;
        back.speed_mps = kEscapeSpeed_mps;
        back.stop_at_wall = false;
        return send(back, Move::kBackUp);
      }
      return escape(false);
    case Move::kBackUp:
    case Move::kCreep:
      if (done) {
        escape_.reset();  // 10 cm driven: out of the pocket
        return resume();
      }
      return escape(false);
    case Move::kEscapeTurn:
      // Free to turn is not free to go: the ladder climbs on if the next move blocks too.
      if (done)
        return resume();
      return escape(true);
    case Move::kNone:
    case Move::kPause:
      break;
  }
}

// ---- status -------------------------------------------------------------------------------------

BehaviourStatus MapBuildingMission::status() const {
  BehaviourStatus s;
  s.phase = std::string(toString(phase_));
  if (phase_ == MapBuildingPhase::kObstacle)
    s.phase.append(1, ' ').append(std::to_string(record_.obstacles().size() + 1));
  s.finished = phase_ == MapBuildingPhase::kDone || phase_ == MapBuildingPhase::kFailed;
  s.failed = phase_ == MapBuildingPhase::kFailed;
  s.message = message_;
  if (phase_ == MapBuildingPhase::kDone)
    s.progress = 1.0;
  else if (!record_.outline())
    s.progress = 0.1 + 0.3 * std::min(1.0, loops_.loopDistance_m() / 40.0);
  else
    s.progress = std::min(0.95, 0.5 + 0.05 * targets_visited_ + 0.05 * obstacleCount());
  return s;
}

}  // namespace irgs
