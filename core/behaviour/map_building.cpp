#include "core/behaviour/map_building.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>

#include "core/motion/turn_control.hpp"
#include "core/motion/position_revision.hpp"
#include "core/planning/path_amendment.hpp"

namespace irgs {
namespace {

constexpr double kApproachLimit_m = 0.8;  // drive at most this far toward a suspected obstacle
constexpr double kApproachSpeed_mps = 0.15;
constexpr double kExploreFree = 0.3;  // long-range knowledge grid: free below this probability
// Wall landmarks (position revision): a later fit must overlap one by this much along the wall,
// and on the same loop be this far of travel later, to move the pose.
constexpr double kLandmarkOverlap_m = 0.3;
constexpr double kLandmarkMinAge_m = 10.0;
// Ranging to room walls: nearer readings are wall following's; the wall's normal must be this
// far inside the cone; the built map must be free up to this short of the wall.
constexpr double kRangingMin_m = 0.4;
constexpr double kRangingConeMargin_rad = 0.05;
constexpr double kRangingClearance_m = 0.35;
// Around the point where an obstacle loop started, no new obstacle target after the loop closed.
constexpr double kAnchorBlacklist_m = 0.5;
constexpr double kMissedAnchorBlacklist_m = 1.2;
constexpr double kPocketMaxArea_m2 = 1.0;  // clockwise obstacle loops smaller than this: pockets //
                                           // when the loop did not enclose it
// At most this many obstacle loops may start within kRevisitRadius_m of one another.
constexpr double kRevisitRadius_m = 1.0;
constexpr int kMaxLoopsNearSpot = 2;
// Learned odometry heading error: bounds (0.57 deg/m; 2 % of the angle turned) and the
// regularisation of the least-squares fit (in m^2 and rad^2: a weak pull towards zero).
constexpr double kMaxDrift_radpm = 0.01;
constexpr double kMaxTurnScaleError = 0.02;
constexpr double kDriftRegularisation = 1.0;

double signedArea(const std::vector<Vec2>& poly) {
  double a = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i)
    a += cross(poly[i], poly[(i + 1) % poly.size()]);
  return 0.5 * a;
}

bool insidePolygon(const std::vector<Vec2>& poly, const Vec2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

double distanceToLoop(const std::vector<Vec2>& loop, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < loop.size(); ++i)
    best = std::min(best, distanceToSegment(p, loop[i], loop[(i + 1) % loop.size()]));
  return best;
}

int floorDiv(int a, int b) {
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

}  // namespace

std::optional<std::string> mapBuildingConfigError(const MapBuildingConfig& c) {
  if (const auto err = wallFollowConfigError(c.follow))
    return "follow: " + *err;
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!std::isfinite(c.turn_quantum_rad) || c.turn_quantum_rad < 0.0 ||
      c.turn_quantum_rad > degToRad(90.0))
    return "turn_quantum_rad must be in [0, 90 deg]";
  if (!positive(c.index_spacing_m) || !positive(c.closure_radius_m) ||
      !positive(c.min_loop_length_m))
    return "index spacing, closure radius and minimum loop length must be > 0";
  if (c.closure_radius_m >= c.min_loop_length_m)
    return "closure_radius_m must be smaller than min_loop_length_m";
  if (!positive(c.map_valid_distance_m) || !positive(c.grid_resolution_m) ||
      !positive(c.explore_cell_m) || c.explore_cell_m < c.grid_resolution_m)
    return "map_valid_distance_m, grid_resolution_m > 0 and explore_cell_m >= grid resolution";
  if (!std::isfinite(c.clearance_margin_m) || c.clearance_margin_m < 0.0)
    return "clearance_margin_m must be >= 0";
  if (!positive(c.travel_speed_mps) || !positive(c.max_time_s) || !positive(c.max_distance_m))
    return "travel speed and budgets must be > 0";
  if (!std::isfinite(c.heading_gate_base_rad) || c.heading_gate_base_rad < 0.0 ||
      !std::isfinite(c.heading_gate_per_m) || c.heading_gate_per_m < 0.0 ||
      !std::isfinite(c.heading_gate_per_turn) || c.heading_gate_per_turn < 0.0 ||
      !std::isfinite(c.heading_confirm_rad) || c.heading_confirm_rad < 0.0)
    return "heading gate and confirmation tolerances must be finite and >= 0";
  if (!std::isfinite(c.heading_walk_rad2_per_m) || c.heading_walk_rad2_per_m < 0.0 ||
      !std::isfinite(c.heading_walk_rad2_per_rad) || c.heading_walk_rad2_per_rad < 0.0 ||
      !positive(c.heading_fit_floor_rad) || !positive(c.obstacle_fit_floor_rad))
    return "heading random walk must be finite and >= 0, fit floors > 0";
  if (!positive(c.wall_ranging_gate_m) || !std::isfinite(c.wall_ranging_gain) ||
      c.wall_ranging_gain <= 0.0 || c.wall_ranging_gain > 1.0)
    return "wall_ranging_gate_m must be > 0 and wall_ranging_gain in (0, 1]";
  if (!positive(c.max_obstacle_loop_m) || c.max_obstacle_loop_m <= c.min_loop_length_m)
    return "max_obstacle_loop_m must be > min_loop_length_m";
  if (!std::isfinite(c.explore_range_m) || c.explore_range_m < 0.0)
    return "explore_range_m must be finite and >= 0";
  if (!positive(c.position_gate_m))
    return "position_gate_m must be > 0";
  if (const auto err = sonarInverseModelError(c.sonar_model))
    return "sonar_model: " + *err;
  return std::nullopt;
}

std::string_view toString(MapBuildingPhase phase) {
  switch (phase) {
    case MapBuildingPhase::kScan:
      return "scan";
    case MapBuildingPhase::kSeekWall:
      return "seek wall";
    case MapBuildingPhase::kFollowWall:
      return "follow wall";
    case MapBuildingPhase::kLoopClosed:
      return "loop closed";
    case MapBuildingPhase::kInterior:
      return "interior";
    case MapBuildingPhase::kObstacle:
      return "obstacle";
    case MapBuildingPhase::kDone:
      return "done";
    case MapBuildingPhase::kFailed:
      return "failed";
  }
  return "?";
}

namespace {
MapBuildingConfig normalised(MapBuildingConfig c) {
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
MapBuildingConfig checked(const MapBuildingConfig& c) {
  if (const auto err = mapBuildingConfigError(c))
    throw std::invalid_argument("MapBuildingConfig: " + *err);
  return normalised(c);
}
}  // namespace

MapBuildingBehaviour::MapBuildingBehaviour(const RobotProfile& profile, MapBuildingConfig config)
    : config_(checked(config)),
      profile_(profile),
      view_(profile, config_.map_valid_distance_m),
      follower_(profile, config_.follow),
      mapper_(profile, config_.sonar_model, config_.map_valid_distance_m),
      grid_(config_.grid_resolution_m),
      explore_mapper_(profile, exploreModel(config_),
                      config_.explore_range_m > 0.0 ? config_.explore_range_m : 1.0),
      explore_grid_(0.5 * config_.explore_cell_m),
      body_radius_m_(profile.bodyRadius()) {}

VelocityCommand MapBuildingBehaviour::fail(const std::string& why) {
  phase_ = MapBuildingPhase::kFailed;
  message_ = why;
  return {};
}

BehaviourStatus MapBuildingBehaviour::status() const {
  BehaviourStatus s;
  s.phase = std::string(toString(phase_));
  if (phase_ == MapBuildingPhase::kObstacle)
    s.phase.append(1, ' ').append(std::to_string(obstacle_loops_.size() + 1));
  s.finished = phase_ == MapBuildingPhase::kDone || phase_ == MapBuildingPhase::kFailed;
  s.failed = phase_ == MapBuildingPhase::kFailed;
  s.message = message_;
  if (phase_ == MapBuildingPhase::kDone)
    s.progress = 1.0;
  else if (!outline_)
    s.progress = 0.1 + 0.3 * std::min(1.0, loop_distance_m_ / 40.0);
  else
    s.progress = std::min(0.95, 0.5 + 0.05 * targets_visited_ + 0.05 * obstacleCount());
  return s;
}

VelocityCommand MapBuildingBehaviour::startFollowing(const Pose2& pose, MapBuildingPhase phase) {
  (void)pose;
  ++follow_epoch_;
  follower_.restart();
  phase_ = phase;
  indices_.clear();
  index_distance_.clear();
  index_heading_.clear();
  loop_distance_m_ = 0.0;
  loop_interior_m_ = 0.0;
  move_ = Move::kNone;
  return {};
}

VelocityCommand MapBuildingBehaviour::scan(const Pose2& pose) {
  // One full on-the-spot turn, CCW, noting the nearest echo ahead in every direction.
  if (const auto front = view_.frontDistance()) {
    if (scan_initial_range_ < 0.0 && scan_turned_rad_ < degToRad(10.0))
      scan_initial_range_ = *front;
    if (scan_best_range_ == 0.0 || *front < scan_best_range_) {
      scan_best_range_ = *front;
      scan_best_heading_ = pose.theta;
    }
  }
  if (scan_turned_rad_ < 2.0 * kPi)
    return {0.0, std::min(0.8, config_.follow.turn_rate_radps)};
  // Prefer the initial heading unless another wall is clearly nearer (each turn adds error).
  double heading = scan_start_heading_;
  if (scan_best_range_ > 0.0 &&
      (scan_initial_range_ < 0.0 || scan_initial_range_ > 1.25 * scan_best_range_ + 0.1))
    heading =
        scan_start_heading_ + quantiseAngle(wrapAngle(scan_best_heading_ - scan_start_heading_),
                                            config_.turn_quantum_rad);
  move_ = Move::kTurn;
  move_heading_ = wrapAngle(heading);
  phase_ = MapBuildingPhase::kSeekWall;
  message_ = "scan done: heading for the nearest wall";
  return {};
}

VelocityCommand MapBuildingBehaviour::onLoopClosed(const Pose2& pose, std::size_t from_index) {
  TracedLoop loop;
  loop.indices.assign(indices_.begin() + static_cast<std::ptrdiff_t>(from_index), indices_.end());
  loop.indices.push_back(pose.position());
  loop.signed_area_m2 = signedArea(loop.indices);
  loop.obstacle = loop.signed_area_m2 > 0.0;
  const bool was_outline_search = phase_ == MapBuildingPhase::kFollowWall;
  const bool was_obstacle = phase_ == MapBuildingPhase::kObstacle;
  ++follow_epoch_;
  phase_ = MapBuildingPhase::kLoopClosed;
  move_ = Move::kPause;
  pause_until_s_ = now_s_ + 1.0;
  if (was_obstacle && obstacle_anchor_) {
    // Whatever the loop looked like, the surface that started it has been followed: never
    // start again from there (a concave pocket of an obstacle closes small clockwise loops).
    // A loop that did not enclose it went round a neighbour instead (obstacles closer than
    // the follower's reach): that surface was seen from close by, so leave its whole
    // neighbourhood to the map rather than trying again from its other faces.
    // (A clockwise loop went round the room along its walls: the obstacle touches a wall
    // through a gap too narrow to pass; it is tried again from elsewhere.)
    const bool missed = loop.obstacle && !insidePolygon(loop.indices, *obstacle_anchor_);
    blacklist(*obstacle_anchor_, missed ? kMissedAnchorBlacklist_m : kAnchorBlacklist_m);
    obstacle_anchors_.push_back(*obstacle_anchor_);
    obstacle_anchor_.reset();
  }
  if (was_obstacle && !loop.obstacle && outline_) {
    // Clockwise inside the room: a small one is a pocket of the obstacle being followed (its
    // surroundings are explained); a large one went round the room along its walls and explains
    // nothing new.
    if (-loop.signed_area_m2 < kPocketMaxArea_m2) {
      pocket_loops_.push_back(loop);
      message_ = "obstacle pocket traced (" + std::to_string(loop.indices.size()) + " indices)";
    } else {
      message_ = "obstacle loop went round the room";
    }
    after_pause_ = MapBuildingPhase::kInterior;
  } else if (loop.obstacle) {
    obstacle_loops_.push_back(loop);
    if (was_outline_search && !outline_) {
      first_wall_was_obstacle_ = obstacle_loops_.size() == 1 ? true : first_wall_was_obstacle_;
      message_ = "loop closed counter-clockwise: the first wall was obstacle " +
                 std::to_string(obstacle_loops_.size()) + "; going on to the real wall";
      after_pause_ = MapBuildingPhase::kSeekWall;
    } else {
      message_ = "obstacle " + std::to_string(obstacle_loops_.size()) + " circumnavigated";
      after_pause_ = outline_ ? MapBuildingPhase::kInterior : MapBuildingPhase::kSeekWall;
    }
  } else {
    if (!outline_)
      outline_ = loop;
    message_ = "outline loop closed (" + std::to_string(loop.indices.size()) + " indices, " +
               std::to_string(static_cast<int>(std::lround(-loop.signed_area_m2))) + " m2)";
    after_pause_ = MapBuildingPhase::kInterior;
  }
  indices_.clear();
  index_distance_.clear();
  index_heading_.clear();
  return {};
}

VelocityCommand MapBuildingBehaviour::followStep(const TelemetrySample& sample, const Pose2& pose) {
  const VelocityCommand cmd = follower_.onSample(sample);
  fitWallHeading(sample);
  if (indices_.empty()) {
    if (!follower_.following())
      return cmd;
    if (phase_ == MapBuildingPhase::kSeekWall)
      phase_ = MapBuildingPhase::kFollowWall;
    indices_.push_back(pose.position());
    index_distance_.push_back(0.0);
    index_heading_.push_back(pose.theta);
    all_indices_.push_back(pose.position());
    loop_distance_m_ = 0.0;
    next_index_at_m_ = config_.index_spacing_m;
    return cmd;
  }
  loop_distance_m_ += (pose.position() - last_pose_.position()).norm();
  if (loop_distance_m_ >= next_index_at_m_) {
    indices_.push_back(pose.position());
    index_distance_.push_back(loop_distance_m_);
    index_heading_.push_back(pose.theta);
    all_indices_.push_back(pose.position());
    next_index_at_m_ += config_.index_spacing_m;
  }
  // An obstacle loop that goes on and on has merged several obstacles packed closer than the
  // follower's reach (or keeps missing its start): what it passed is mapped and explained;
  // give it up and go on with the interior.
  if (phase_ == MapBuildingPhase::kObstacle && outline_ &&
      distanceToLoop(outline_->indices, pose.position()) > config_.follow.distance_m + 0.3)
    loop_interior_m_ += (pose.position() - last_pose_.position()).norm();
  if (phase_ == MapBuildingPhase::kObstacle && loop_interior_m_ > config_.max_obstacle_loop_m) {
    TracedLoop partial;
    partial.indices = indices_;
    pocket_loops_.push_back(partial);
    if (obstacle_anchor_) {
      blacklist(*obstacle_anchor_, kMissedAnchorBlacklist_m);
      obstacle_anchors_.push_back(*obstacle_anchor_);
      obstacle_anchor_.reset();
    }
    indices_.clear();
    index_distance_.clear();
    index_heading_.clear();
    ++follow_epoch_;
    message_ = "obstacle loop given up after " +
               std::to_string(static_cast<int>(config_.max_obstacle_loop_m)) + " m";
    phase_ = MapBuildingPhase::kLoopClosed;
    after_pause_ = MapBuildingPhase::kInterior;
    move_ = Move::kPause;
    pause_until_s_ = now_s_ + 1.0;
    return {};
  }
  // Back at an earlier index, heading the same way, after a real loop: closed.
  if (follower_.following()) {
    for (std::size_t i = 0; i < indices_.size(); ++i) {
      if (loop_distance_m_ - index_distance_[i] < config_.min_loop_length_m)
        break;
      if ((pose.position() - indices_[i]).norm() < config_.closure_radius_m &&
          std::abs(wrapAngle(pose.theta - index_heading_[i])) < degToRad(60.0))
        return onLoopClosed(pose, i);
    }
  }
  return cmd;
}

bool MapBuildingBehaviour::explained(const Vec2& p) const {
  const double margin = config_.follow.distance_m + 0.3;
  if (outline_ && distanceToLoop(outline_->indices, p) < margin)
    return true;
  for (const TracedLoop& loop : obstacle_loops_)
    if (insidePolygon(loop.indices, p) || distanceToLoop(loop.indices, p) < margin)
      return true;
  for (const TracedLoop& loop : pocket_loops_)
    if (distanceToLoop(loop.indices, p) < margin)
      return true;
  return false;
}

bool MapBuildingBehaviour::visitedOften(const Vec2& p) const {
  // Obstacles packed closer than the follower's reach (a post in a narrow aisle between boxes)
  // merge into loops round several of them, pockets and fragments; after a few loops started
  // near a spot, what is left there has been seen from close by and is mapped, not circled.
  int loops = 0;
  for (const Vec2& a : obstacle_anchors_)
    loops += (a - p).norm() < kRevisitRadius_m ? 1 : 0;
  return loops >= kMaxLoopsNearSpot;
}

void MapBuildingBehaviour::blacklist(const Vec2& p, double radius_m) {
  blacklist_.push_back(p);
  blacklist_radius_.push_back(radius_m);
}

std::optional<MapBuildingBehaviour::Target> MapBuildingBehaviour::chooseTarget(const Pose2& pose) {
  if (!outline_)
    return std::nullopt;
  const double res = grid_.resolution_m();
  const int f = std::max(1, static_cast<int>(std::lround(config_.explore_cell_m / res)));
  const double cell = f * res;
  const OccupancyGrid::CellRect rect = grid_.observedCellRect();
  if (rect.empty())
    return std::nullopt;
  std::vector<float> values;
  grid_.copyLogOdds(rect, values);
  const int cc0 = floorDiv(rect.col0, f) - 1, cr0 = floorDiv(rect.row0, f) - 1;
  const int W = floorDiv(rect.col1, f) - cc0 + 2, H = floorDiv(rect.row1, f) - cr0 + 2;
  const auto at = [W](int c, int r) {
    return static_cast<std::size_t>(r) * static_cast<std::size_t>(W) + static_cast<std::size_t>(c);
  };
  std::vector<int> observed(static_cast<std::size_t>(W * H), 0),
      occupied(static_cast<std::size_t>(W * H), 0);
  const float occ_threshold = 0.62f;  // p = 0.65
  for (int r = 0; r < rect.height(); ++r)
    for (int c = 0; c < rect.width(); ++c) {
      const float v = values[static_cast<std::size_t>(r * rect.width() + c)];
      if (std::isnan(v))
        continue;
      const std::size_t k = at(floorDiv(rect.col0 + c, f) - cc0, floorDiv(rect.row0 + r, f) - cr0);
      ++observed[k];
      if (v > occ_threshold)
        ++occupied[k];
    }
  const auto centre = [&](int c, int r) {
    return Vec2((cc0 + c + 0.5) * cell, (cr0 + r + 0.5) * cell);
  };
  enum : std::uint8_t { kUnknown, kFree, kOcc };
  std::vector<std::uint8_t> state(static_cast<std::size_t>(W * H), kUnknown);
  for (std::size_t k = 0; k < state.size(); ++k)
    state[k] = occupied[k] >= 2 ? kOcc : (observed[k] * 2 >= f * f ? kFree : kUnknown);
  // Free space seen at long range (explore_range_m) is known too: no need to drive within the
  // mapping range of every open spot. Obstacles still come from the mapping grid only.
  if (config_.explore_range_m > 0.0)
    for (int r = 0; r < H; ++r)
      for (int c = 0; c < W; ++c) {
        if (state[at(c, r)] != kUnknown)
          continue;
        const Cell e = explore_grid_.cellAt(centre(c, r));
        if (explore_grid_.observed(e) && explore_grid_.probability(e) < kExploreFree)
          state[at(c, r)] = kFree;
      }
  // Blocked for travel: occupied grown by the body radius plus a margin; unknown.
  const double inflate_m = body_radius_m_ + config_.clearance_margin_m;
  const int rad = static_cast<int>(std::ceil(inflate_m / cell));
  std::vector<std::uint8_t> blocked(state.size(), 0);
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) {
      if (state[at(c, r)] == kUnknown)
        blocked[at(c, r)] = 1;
      if (state[at(c, r)] != kOcc)
        continue;
      for (int dr = -rad; dr <= rad; ++dr)
        for (int dc = -rad; dc <= rad; ++dc) {
          const int x = c + dc, y = r + dr;
          if (x < 0 || y < 0 || x >= W || y >= H)
            continue;
          if (std::hypot(dc, dr) * cell <= inflate_m + 0.5 * cell)
            blocked[at(x, y)] = 1;
        }
    }
  const int rc = static_cast<int>(std::floor(pose.x / cell)) - cc0;
  const int rr = static_cast<int>(std::floor(pose.y / cell)) - cr0;
  if (rc < 0 || rr < 0 || rc >= W || rr >= H)
    return std::nullopt;
  const auto listed = [&](const Vec2& p) {
    for (std::size_t i = 0; i < blacklist_.size(); ++i)
      if ((p - blacklist_[i]).norm() < blacklist_radius_[i])
        return true;
    return false;
  };
  // A robot that ended a loop beside an obstacle stands inside its inflated band: known free
  // cells that near the robot stay passable, so it can plan its way out instead of finding
  // nothing to do.
  const auto passable = [&](int x, int y) {
    if (!blocked[at(x, y)])
      return true;
    return state[at(x, y)] == kFree && std::hypot(x - rc, y - rr) * cell <= inflate_m + cell;
  };
  // Dijkstra (8-connected, costs 10 / 14) from the robot's cell.
  std::vector<int> cost(state.size(), std::numeric_limits<int>::max());
  std::vector<std::int64_t> parent(state.size(), -1);
  using Item = std::pair<int, std::int64_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  cost[at(rc, rr)] = 0;
  open.push({0, static_cast<std::int64_t>(at(rc, rr))});
  const double near_obstacle_m = inflate_m + 0.25;
  const int near = static_cast<int>(std::ceil(near_obstacle_m / cell));
  while (!open.empty()) {
    const auto [d, k] = open.top();
    open.pop();
    if (d != cost[static_cast<std::size_t>(k)])
      continue;
    const int c = static_cast<int>(k % W), r = static_cast<int>(k / W);
    const Vec2 p = centre(c, r);
    const bool inside = insidePolygon(outline_->indices, p);
    // Beyond the outline (another room through a doorway the wall follower passed as a gap,
    // or space the first loop cut off) only frontiers count: obstacles there are mapped as
    // they are passed, not circumnavigated.
    if ((inside || config_.explore_beyond_outline) && d > 0 && !listed(p)) {
      Target t;
      t.position = p;
      // An unvisited obstacle within reach of this cell?
      bool found = false;
      for (int dr = -near; dr <= near && inside && !found; ++dr)
        for (int dc = -near; dc <= near && !found; ++dc) {
          const int x = c + dc, y = r + dr;
          if (x < 0 || y < 0 || x >= W || y >= H || state[at(x, y)] != kOcc)
            continue;
          const Vec2 o = centre(x, y);
          if ((o - p).norm() > near_obstacle_m || !insidePolygon(outline_->indices, o) ||
              explained(o) || listed(o) || visitedOften(o))
            continue;
          t.obstacle = true;
          t.obstacle_point = o;
          found = true;
        }
      // Or a frontier: enough unknown cells next to this one.
      if (!found) {
        int unknown = 0;
        for (int dr = -2; dr <= 2; ++dr)
          for (int dc = -2; dc <= 2; ++dc) {
            const int x = c + dc, y = r + dr;
            if (x >= 0 && y >= 0 && x < W && y < H && state[at(x, y)] == kUnknown &&
                (config_.explore_beyond_outline || insidePolygon(outline_->indices, centre(x, y))))
              ++unknown;
          }
        found = unknown >= 4;
      }
      if (found) {
        std::vector<Vec2> cells;
        for (std::int64_t q = k; q >= 0; q = parent[static_cast<std::size_t>(q)])
          cells.push_back(centre(static_cast<int>(q % W), static_cast<int>(q / W)));
        std::reverse(cells.begin(), cells.end());
        cells.front() = pose.position();
        t.path = compressPath(cells);
        return t;
      }
    }
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        if (dr == 0 && dc == 0)
          continue;
        const int x = c + dc, y = r + dr;
        if (x < 0 || y < 0 || x >= W || y >= H || !passable(x, y))
          continue;
        // No corner cutting past a blocked cell.
        if (dr != 0 && dc != 0 && (!passable(c + dc, r) || !passable(c, r + dr)))
          continue;
        const int nd = d + (dr != 0 && dc != 0 ? 14 : 10);
        if (nd < cost[at(x, y)]) {
          cost[at(x, y)] = nd;
          parent[at(x, y)] = k;
          open.push({nd, static_cast<std::int64_t>(at(x, y))});
        }
      }
  }
  return std::nullopt;
}

VelocityCommand MapBuildingBehaviour::interior(const TelemetrySample& sample, const Pose2& pose) {
  (void)sample;
  const auto front = view_.frontDistance();
  const bool wall_ahead =
      front && *front < config_.follow.distance_m + config_.follow.front_margin_m;
  switch (move_) {
    case Move::kNone: {
      target_ = chooseTarget(pose);
      if (!target_) {
        phase_ = MapBuildingPhase::kDone;
        message_ = "map complete: outline closed, " + std::to_string(obstacleCount()) +
                   " obstacle(s), no reachable unknown area left";
        return {};
      }
      waypoint_ = 1;
      if (target_->path.size() < 2) {
        move_ = Move::kDrive;  // already there
        move_length_m_ = 0.0;
        move_start_ = pose.position();
        return {};
      }
      move_ = Move::kTurn;
      move_heading_ = std::atan2((target_->path[1] - pose.position()).y(),
                                 (target_->path[1] - pose.position()).x());
      return {};
    }
    case Move::kDrive: {
      const double travelled = (pose.position() - move_start_).norm();
      if (wall_ahead) {
        const Vec2 hit = pose.position() + *front * pose.heading();
        if (outline_ && insidePolygon(outline_->indices, hit) && !explained(hit) &&
            !visitedOften(hit)) {
          message_ = "obstacle met: circumnavigate counter-clockwise";
          obstacle_anchor_ = hit;
          return startFollowing(pose, MapBuildingPhase::kObstacle);
        }
        blacklist(target_->position, 0.3);
        move_ = Move::kNone;
        return {};
      }
      if (travelled < move_length_m_)
        return straightCommand(pose.theta, move_heading_, config_.travel_speed_mps);
      if (++waypoint_ < target_->path.size()) {
        move_ = Move::kTurn;
        const Vec2 d = target_->path[waypoint_] - pose.position();
        move_heading_ = std::atan2(d.y(), d.x());
        return {};
      }
      ++targets_visited_;
      if (target_->obstacle) {
        move_ = Move::kFaceObstacle;
        const Vec2 d = target_->obstacle_point - pose.position();
        move_heading_ = std::atan2(d.y(), d.x());
        return {};
      }
      blacklist(target_->position, 0.4);
      move_ = Move::kNone;
      return {};
    }
    case Move::kApproach: {
      if (wall_ahead) {
        message_ = "obstacle reached: circumnavigate counter-clockwise";
        obstacle_anchor_ = pose.position() + *front * pose.heading();
        return startFollowing(pose, MapBuildingPhase::kObstacle);
      }
      if ((pose.position() - move_start_).norm() > kApproachLimit_m) {
        blacklist(target_->obstacle_point, 0.3);
        move_ = Move::kNone;
        return {};
      }
      return straightCommand(pose.theta, move_heading_, kApproachSpeed_mps);
    }
    default:
      move_ = Move::kNone;
      return {};
  }
}

void MapBuildingBehaviour::fitWallHeading(const TelemetrySample& sample) {
  if (config_.heading_lattice_rad <= 0.0 || !follower_.following()) {
    wall_points_.clear();
    pending_error_.reset();
    return;
  }
  // Echo points of the wall-side sonars in the revised frame. Fitting a line through a metre of
  // them measures the wall direction on a long baseline, unlike one pair of readings.
  const SonarRoles::SidePair& pair = view_.roles().left;
  const double present = config_.follow.distance_m + config_.follow.lost_margin_m;
  for (const SonarReading& r : sample.sonar) {
    if ((r.sensor != pair.front && r.sensor != pair.rear) || !r.echo || !std::isfinite(r.range_m))
      continue;
    const Pose2& mount = profile_.sonars[static_cast<std::size_t>(r.sensor)].mount;
    if (r.range_m + std::abs(mount.y) > present)
      continue;
    const Pose2 sensor = pose_.compose(mount);
    wall_points_.push_back(sensor.position() + r.range_m * sensor.heading());
  }
  if (wall_points_.size() < 8 ||
      (wall_points_.back() - wall_points_.front()).norm() < config_.heading_fit_length_m)
    return;
  // Principal direction of the points (total least squares) and the spread across it.
  Vec2 mean = Vec2::Zero();
  for (const Vec2& p : wall_points_)
    mean += p;
  mean /= static_cast<double>(wall_points_.size());
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (const Vec2& p : wall_points_) {
    const Vec2 d = p - mean;
    sxx += d.x() * d.x();
    syy += d.y() * d.y();
    sxy += d.x() * d.y();
  }
  const double n = static_cast<double>(wall_points_.size());
  const double dir = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  const double tr = (sxx + syy) / n, det = (sxx * syy - sxy * sxy) / (n * n);
  const double minor = 0.5 * tr - std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
  if (std::sqrt(std::max(0.0, minor)) > 0.015) {
    // Not one straight wall (a corner or clutter inside): drop the older half and go on.
    wall_points_.erase(wall_points_.begin(),
                       wall_points_.begin() + static_cast<std::ptrdiff_t>(wall_points_.size() / 2));
    return;
  }
  // Extent of the fitted wall along its direction, relative to the mean (for the landmarks).
  double along_min = 0.0, along_max = 0.0;
  for (const Vec2& p : wall_points_) {
    const double a = (p - mean).dot(Vec2(std::cos(dir), std::sin(dir)));
    along_min = std::min(along_min, a);
    along_max = std::max(along_max, a);
  }
  wall_points_.clear();
  double error = wrapAngle(quantiseAngle(dir, config_.heading_lattice_rad) - dir);
  // Obstacles may have any shape: only a face already close to the lattice counts.
  const double capture = phase_ == MapBuildingPhase::kObstacle
                             ? config_.obstacle_heading_capture_rad
                             : config_.heading_capture_rad;
  if (std::abs(error) > capture) {
    pending_error_.reset();
    return;
  }
  const double since = distance_m_ - distance_at_correction_;
  const double gate = config_.heading_gate_base_rad + config_.heading_gate_per_m * since +
                      config_.heading_gate_per_turn * turned_since_correction_rad_;
  const bool confirmed =
      pending_error_ && std::abs(error - *pending_error_) <= config_.heading_confirm_rad;
  if (std::abs(error) > gate && !confirmed) {
    // Larger than the drift can explain: one line is not enough. On the outline the next fit
    // may confirm it; an obstacle face never does on its own.
    ++heading_rejections_;
    if (phase_ == MapBuildingPhase::kObstacle)
      pending_error_.reset();
    else
      pending_error_ = error;
    return;
  }
  pending_error_.reset();
  // How much of the measured error to apply (scalar Kalman update on the heading): the fitted
  // direction has variance sigma^2 / sum(along^2) (residual across the line over the spread
  // along it) plus a floor for walls not exactly on the lattice; the heading's own variance
  // grew with the distance and angle driven since the last revision. One noisy line then nudges
  // the heading instead of replacing it, and successive lines on a long wall average.
  const double fit_variance =
      std::max(0.0, minor) / std::max(1e-9, n * std::max(1e-9, tr - minor)) +
      std::pow(phase_ == MapBuildingPhase::kObstacle ? config_.obstacle_fit_floor_rad
                                                     : config_.heading_fit_floor_rad,
               2);
  const double gain = heading_variance_ / (heading_variance_ + fit_variance);
  const double measured = error;  // raw odometry error seen by this line (for the model below)
  error *= gain;
  heading_variance_ *= 1.0 - gain;
  heading_offset_ = wrapAngle(heading_offset_ + error);
  // Rotate the pose about the fitted wall's centre, so the wall the robot is beside stays
  // where it was mapped and only the heading (and what follows) is revised.
  const Vec2 rel = pose_.position() - mean;
  const double c = std::cos(error), s = std::sin(error);
  pose_.x = mean.x() + c * rel.x() - s * rel.y();
  pose_.y = mean.y() + s * rel.x() + c * rel.y();
  pose_.theta = wrapAngle(pose_.theta + error);
  ++heading_corrections_;
  // The revisions also calibrate the odometry. The heading revised so far against the raw
  // odometry, R = (model applied) + (revisions accepted), is what the odometry got wrong since
  // the start; unequal wheel radii make it grow with the distance driven, a wrong wheelbase with
  // the signed angle turned:
  //   R_i = a * D_i + k * T_i   (a rad/m, k rad/rad; D, T cumulative since the start)
  // a and k are the least-squares fit over all accepted revisions (lightly regularised and
  // bounded). Fitting the cumulative error, not the error between two revisions, keeps the fit
  // noise of one line (~0.2 deg) from being divided by a short baseline: in a room without any
  // odometry error the learned drift stays near zero instead of turning long interior legs.
  const double d = cumulative_distance_m_, t = cumulative_turn_rad_;
  const double total = cumulative_correction_rad_ + measured;
  cumulative_correction_rad_ += error;
  drift_normal_[0] += d * d;
  drift_normal_[1] += d * t;
  drift_normal_[2] += t * t;
  drift_rhs_[0] += d * total;
  drift_rhs_[1] += t * total;
  const double n00 = drift_normal_[0] + kDriftRegularisation, n01 = drift_normal_[1],
               n11 = drift_normal_[2] + kDriftRegularisation;
  const double normal_det = n00 * n11 - n01 * n01;
  if (normal_det > 0.0) {
    drift_radpm_ = std::clamp((n11 * drift_rhs_[0] - n01 * drift_rhs_[1]) / normal_det,
                              -kMaxDrift_radpm, kMaxDrift_radpm);
    turn_scale_error_ = std::clamp((n00 * drift_rhs_[1] - n01 * drift_rhs_[0]) / normal_det,
                                   -kMaxTurnScaleError, kMaxTurnScaleError);
  }
  distance_at_correction_ = distance_m_;
  turned_since_correction_rad_ = 0.0;
  reviseAcrossWall(dir + measured, mean, along_min, along_max);
}

void MapBuildingBehaviour::reviseAcrossWall(double direction, const Vec2& mean, double along_min,
                                            double along_max) {
  // Lines are kept undirected, direction in [0, pi), with the side the robot saw them from
  // (wall on the left: driving along +direction or against it), so that the two faces of a thin
  // obstacle are different landmarks.
  double q = std::fmod(direction, kPi);
  if (q < 0.0)
    q += kPi;
  if (q >= kPi - 1e-9)
    q = 0.0;
  const Vec2 t(std::cos(q), std::sin(q));
  const Vec2 n(-t.y(), t.x());
  WallLandmark seen{q,
                    n.dot(mean),
                    t.dot(mean) + along_min,
                    t.dot(mean) + along_max,
                    std::cos(pose_.theta - q) >= 0.0,
                    follow_epoch_,
                    distance_m_,
                    phase_ == MapBuildingPhase::kFollowWall && !outline_};
  const auto same_line = [&](const WallLandmark& w) {
    return w.forward == seen.forward && std::abs(wrapAngle(2.0 * (w.direction - q))) <= 1e-6;
  };
  const auto overlap = [&](const WallLandmark& w) {
    return std::min(w.along_max, seen.along_max) - std::max(w.along_min, seen.along_min);
  };
  // The same wall seen again (same direction and side, overlapping, offset within the gate),
  // on another loop or long enough ago that the drift since may show, moves the pose across it
  // to where the wall was first mapped: the map stays consistent (no wall drawn twice) and the
  // first loop round the room, which has the least drift, anchors the rest. An ambiguous match
  // (another parallel landmark near) moves nothing. A wall not seen before becomes a landmark.
  const WallLandmark* match = nullptr;
  bool known = false;
  for (const WallLandmark& w : landmarks_) {
    if (!same_line(w) || overlap(w) < kLandmarkOverlap_m)
      continue;
    const double off = std::abs(w.offset - seen.offset);
    if (off >= config_.position_gate_m)
      continue;
    known = true;
    if (w.epoch == seen.epoch && seen.distance_m - w.distance_m < kLandmarkMinAge_m)
      continue;
    if (!match || off < std::abs(match->offset - seen.offset))
      match = &w;
  }
  if (!known) {
    landmarks_.push_back(seen);
    return;
  }
  if (!match || !config_.position_revision)
    return;
  // Several landmarks on one line (pieces of one wall) agree; parallel walls near do not.
  for (const WallLandmark& w : landmarks_)
    if (same_line(w) && std::abs(w.offset - match->offset) > 0.05 &&
        std::abs(w.offset - seen.offset) < 2.0 * config_.position_gate_m &&
        overlap(w) >= kLandmarkOverlap_m)
      return;
  const double shift = match->offset - seen.offset;
  pose_.x += shift * n.x();
  pose_.y += shift * n.y();
  ++position_corrections_;
}

void MapBuildingBehaviour::rangeToRoomWalls(const TelemetrySample& sample) {
  // Revision (d) carried further: a sonar that points (within its cone) straight at a room
  // wall traced on the first loop measures the distance across that wall, whatever the
  // heading error, because the nearest return in the cone is the perpendicular one. Between
  // wall-following runs (long interior legs, obstacle loops) this pins the position across the
  // room walls, which heading revisions alone cannot: the map of the interior then stays on the
  // outline. Readings are gated (within wall_ranging_gate_m of the prediction), need a clear
  // built map between the sensor and the wall (an obstacle in front would return first), and
  // move the pose by a fraction of the disagreement, so a stray echo nudges rather than jumps.
  for (const SonarReading& r : sample.sonar) {
    if (!r.echo || !std::isfinite(r.range_m) || r.sensor < 0 ||
        static_cast<std::size_t>(r.sensor) >= profile_.sonars.size())
      continue;
    const SonarSpec& spec = profile_.sonars[static_cast<std::size_t>(r.sensor)];
    if (r.range_m < kRangingMin_m || r.range_m > spec.max_range_m - 0.1)
      continue;
    const Pose2 sensor = pose_.compose(spec.mount);
    const Vec2 u = sensor.heading();
    const double cos_limit =
        std::cos(std::max(0.0, 0.5 * spec.beam_width_rad - kRangingConeMargin_rad));
    const WallLandmark* best = nullptr;
    double best_predicted = 0.0;
    Vec2 best_normal = Vec2::Zero();
    for (const WallLandmark& w : landmarks_) {
      if (!w.room)
        continue;
      const Vec2 t(std::cos(w.direction), std::sin(w.direction));
      const Vec2 n(-t.y(), t.x());
      const double signed_distance = n.dot(sensor.position()) - w.offset;
      const double side = signed_distance >= 0.0 ? 1.0 : -1.0;
      const double predicted = std::abs(signed_distance);
      // The wall's normal towards it must lie inside the cone.
      if (u.dot(-side * n) < cos_limit)
        continue;
      // The foot of the perpendicular on the traced piece of wall.
      const double along = t.dot(sensor.position());
      if (along < w.along_min - 0.1 || along > w.along_max + 0.1)
        continue;
      if (std::abs(predicted - r.range_m) > config_.wall_ranging_gate_m)
        continue;
      if (!best || predicted < best_predicted) {
        best = &w;
        best_predicted = predicted;
        best_normal = -side * n;  // from the sensor towards the wall
      }
    }
    if (!best)
      continue;
    // Nothing mapped between the sensor and the wall (centre and both cone edges).
    bool clear = true;
    for (int edge = -1; edge <= 1 && clear; ++edge) {
      const double a = sensor.theta + edge * 0.5 * spec.beam_width_rad;
      const Vec2 dir(std::cos(a), std::sin(a));
      const double reach =
          (best_predicted - kRangingClearance_m) / std::max(0.2, dir.dot(best_normal));
      for (double d = 0.1; d < reach && clear; d += 0.5 * config_.explore_cell_m) {
        const Vec2 q = sensor.position() + d * dir;
        clear = grid_.isAddressable(q) && grid_.probability(grid_.cellAt(q)) < 0.65;
      }
    }
    if (!clear)
      continue;
    // Move along the normal so that the predicted distance approaches the measured one.
    const double innovation = best_predicted - r.range_m;  // > 0: closer to the wall than thought
    pose_.x += config_.wall_ranging_gain * innovation * best_normal.x();
    pose_.y += config_.wall_ranging_gain * innovation * best_normal.y();
    ++range_corrections_;
  }
}

// A move of the behaviour's own (interior exploration) that is blocked — in contact for the wall
// follower's blocked_s, the wheels stalled — would wait forever for progress that cannot come:
// the escape ladder picks the next move to try, and after it the behaviour re-plans.
void MapBuildingBehaviour::escapeBlockedMove(const TelemetrySample& sample, const Pose2& pose) {
  const bool turning =
      move_ == Move::kTurn || move_ == Move::kFaceObstacle || move_ == Move::kEscapeTurn;
  const bool escapable = turning || move_ == Move::kBackUp || move_ == Move::kCreep;
  if (!inContact(sample) || !escapable) {
    contact_since_s_.reset();
    return;
  }
  if (!contact_since_s_) {
    contact_since_s_ = sample.time_s;
    return;
  }
  if (sample.time_s - *contact_since_s_ < config_.follow.blocked_s)
    return;
  contact_since_s_.reset();
  move_start_ = pose.position();
  turn_progress_ = {};
  switch (escape_.next(turning)) {
    case EscapeMove::kBackUp:
      move_ = Move::kBackUp;
      break;
    case EscapeMove::kForward:
      move_ = Move::kCreep;
      break;
    case EscapeMove::kTurn:
      move_ = Move::kEscapeTurn;
      move_heading_ = wrapAngle(pose.theta - kEscapeTurn_rad);
      break;
    case EscapeMove::kTurnOpposite:
      move_ = Move::kEscapeTurn;
      move_heading_ = wrapAngle(pose.theta + kEscapeTurn_rad);
      break;
  }
}

VelocityCommand MapBuildingBehaviour::onSample(const TelemetrySample& raw) {
  now_s_ = raw.time_s;
  if (phase_ == MapBuildingPhase::kDone || phase_ == MapBuildingPhase::kFailed)
    return {};
  const Pose2& odo = raw.odometry_pose;
  if (!std::isfinite(odo.x) || !std::isfinite(odo.y) || !std::isfinite(odo.theta))
    return fail("odometry pose is not finite");
  if (!started_) {
    pose_ = odo;
    last_odometry_ = odo;
  }
  // Carry the odometry increment (body frame of the previous odometry pose) onto the revised
  // pose: the heading revisions rotate everything driven after them.
  const Vec2 step_body = last_odometry_.toBody(odo.position());
  const double odo_turn = wrapAngle(odo.theta - last_odometry_.theta);
  // The learned error model (fitWallHeading) removed from every step.
  const double model = drift_radpm_ * step_body.norm() + turn_scale_error_ * odo_turn;
  const double step_turn = odo_turn + model;
  pose_ = pose_.compose({step_body.x(), step_body.y(), step_turn});
  turned_since_correction_rad_ += std::abs(odo_turn);
  cumulative_distance_m_ += step_body.norm();
  heading_variance_ += config_.heading_walk_rad2_per_m * step_body.norm() +
                       config_.heading_walk_rad2_per_rad * std::abs(odo_turn);
  cumulative_turn_rad_ += odo_turn;
  cumulative_correction_rad_ += model;
  last_odometry_ = odo;
  if (started_ && outline_ && config_.wall_ranging)
    rangeToRoomWalls(raw);
  TelemetrySample sample = raw;
  sample.odometry_pose = pose_;
  const Pose2 pose = pose_;
  view_.update(sample);
  mapper_.integrate(sample, grid_);
  if (config_.explore_range_m > 0.0)
    explore_mapper_.integrate(sample, explore_grid_);
  if (!started_) {
    started_ = true;
    start_time_s_ = sample.time_s;
    last_pose_ = pose;
    scan_start_heading_ = pose.theta;
  }
  distance_m_ += (pose.position() - last_pose_.position()).norm();
  if (phase_ == MapBuildingPhase::kScan)
    scan_turned_rad_ += std::abs(wrapAngle(pose.theta - last_pose_.theta));

  escapeBlockedMove(sample, pose);
  VelocityCommand cmd;
  if (sample.time_s - start_time_s_ > config_.max_time_s) {
    cmd = fail("time budget of " + std::to_string(static_cast<int>(config_.max_time_s)) +
               " s used up in phase '" + std::string(toString(phase_)) + "'");
  } else if (distance_m_ > config_.max_distance_m) {
    cmd = fail("distance budget of " + std::to_string(static_cast<int>(config_.max_distance_m)) +
               " m used up in phase '" + std::string(toString(phase_)) + "'");
  } else if (move_ == Move::kTurn || move_ == Move::kFaceObstacle || move_ == Move::kEscapeTurn) {
    const TurnStep turn =
        turnStep(turn_progress_, pose.theta, move_heading_, sample.measured_velocity.angular_radps,
                 config_.follow.turn_rate_radps);
    if (turn.done) {
      turn_progress_ = {};  // the next turn starts afresh, even toward the same heading
      view_.forgetBefore(sample.time_s);
      // A turn of the plan's completed: the body is free again. An escape turn does not count
      // (free to turn is not free to go): if the next move blocks too, the ladder climbs on.
      if (move_ != Move::kEscapeTurn)
        escape_.reset();
      if (move_ == Move::kEscapeTurn) {
        move_ = Move::kNone;
      } else if (phase_ == MapBuildingPhase::kSeekWall) {
        cmd = startFollowing(pose, MapBuildingPhase::kSeekWall);
      } else if (move_ == Move::kFaceObstacle) {
        move_ = Move::kApproach;
        move_start_ = pose.position();
      } else {
        move_ = Move::kDrive;
        move_start_ = pose.position();
        move_length_m_ = target_ && waypoint_ < target_->path.size()
                             ? (target_->path[waypoint_] - pose.position()).norm()
                             : 0.0;
      }
    } else {
      cmd = {0.0, turn.angular_radps};
    }
  } else if (move_ == Move::kBackUp || move_ == Move::kCreep) {
    const double speed = move_ == Move::kBackUp ? -0.1 : 0.1;
    if ((pose.position() - move_start_).norm() > 0.1) {
      move_ = Move::kNone;
      escape_.reset();  // 10 cm driven: out of the pocket
    } else {
      cmd = {speed, 0.0};
    }
  } else if (move_ == Move::kPause) {
    if (sample.time_s >= pause_until_s_) {
      move_ = Move::kNone;
      if (after_pause_ == MapBuildingPhase::kSeekWall) {
        // Turn away from the obstacle just traced (it is on the left) and seek the wall.
        move_ = Move::kTurn;
        move_heading_ = wrapAngle(pose.theta - 0.5 * kPi);
        phase_ = MapBuildingPhase::kSeekWall;
      } else {
        phase_ = after_pause_;
      }
    }
  } else {
    switch (phase_) {
      case MapBuildingPhase::kScan:
        cmd = scan(pose);
        break;
      case MapBuildingPhase::kSeekWall:
      case MapBuildingPhase::kFollowWall:
      case MapBuildingPhase::kObstacle:
        cmd = followStep(sample, pose);
        break;
      case MapBuildingPhase::kInterior:
        if (inContact(sample)) {
          move_ = Move::kBackUp;
          move_start_ = pose.position();
          if (target_)
            blacklist(target_->position, 0.3);
          cmd = {-0.1, 0.0};
        } else {
          cmd = interior(sample, pose);
        }
        break;
      default:
        break;
    }
  }
  last_pose_ = pose;
  return cmd;
}

}  // namespace irgs
