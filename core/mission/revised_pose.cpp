#include "core/mission/revised_pose.hpp"

#include <algorithm>
#include <cmath>

#include "core/motion/host_adapters.hpp"
#include "core/motion/position_revision.hpp"

namespace irgs {
namespace {

// Wall landmarks (position revision): a later fit must overlap one by this much along the wall,
// and on the same loop be this far of travel later, to move the pose.
constexpr double kLandmarkOverlap_m = 0.3;
constexpr double kLandmarkMinAge_m = 10.0;
// Ranging to room walls: nearer readings are wall following's; the wall's normal must be this
// far inside the cone; the built map must be free up to this short of the wall.
constexpr double kRangingMin_m = 0.4;
constexpr double kRangingConeMargin_rad = 0.05;
constexpr double kRangingClearance_m = 0.35;
// Learned odometry heading error: bounds (0.57 deg/m; 2 % of the angle turned) and the
// regularisation of the least-squares fit (in m^2 and rad^2: a weak pull towards zero).
constexpr double kMaxDrift_radpm = 0.01;
constexpr double kMaxTurnScaleError = 0.02;
constexpr double kDriftRegularisation = 1.0;

}  // namespace

RevisedPose::RevisedPose(const RobotProfile& profile, const MapBuildingConfig& config)
    : config_(config),
      profile_(profile),
      roles_(motion::findSonarRoles(motion::motionGeometryOf(profile))) {}

void RevisedPose::onOdometry(const Pose2& odo) {
  if (!started_) {
    started_ = true;
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
}

Pose2 RevisedPose::odometryOf(const Pose2& map_pose) const {
  return last_odometry_.compose(pose_.inverse().compose(map_pose));
}

void RevisedPose::fitWall(const TelemetrySample& sample, const WallContext& context) {
  if (config_.heading_lattice_rad <= 0.0 || !context.following) {
    wall_points_.clear();
    pending_error_.reset();
    return;
  }
  // Echo points of the wall-side sonars in the revised frame. Fitting a line through a metre of
  // them measures the wall direction on a long baseline, unlike one pair of readings.
  const motion::SonarRoles::SidePair& pair = roles_.left;
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
  const double capture =
      context.obstacle ? config_.obstacle_heading_capture_rad : config_.heading_capture_rad;
  if (std::abs(error) > capture) {
    pending_error_.reset();
    return;
  }
  const double since = context.distance_m - distance_at_correction_;
  const double gate = config_.heading_gate_base_rad + config_.heading_gate_per_m * since +
                      config_.heading_gate_per_turn * turned_since_correction_rad_;
  const bool confirmed =
      pending_error_ && std::abs(error - *pending_error_) <= config_.heading_confirm_rad;
  if (std::abs(error) > gate && !confirmed) {
    // Larger than the drift can explain: one line is not enough. On the outline the next fit
    // may confirm it; an obstacle face never does on its own.
    ++heading_rejections_;
    if (context.obstacle)
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
      std::pow(context.obstacle ? config_.obstacle_fit_floor_rad : config_.heading_fit_floor_rad,
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
  distance_at_correction_ = context.distance_m;
  turned_since_correction_rad_ = 0.0;
  reviseAcrossWall(dir + measured, mean, along_min, along_max, context);
}

void RevisedPose::reviseAcrossWall(double direction, const Vec2& mean, double along_min,
                                   double along_max, const WallContext& context) {
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
                    context.epoch,
                    context.distance_m,
                    context.room_first_loop};
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

void RevisedPose::rangeToRoomWalls(const TelemetrySample& sample, const OccupancyGrid& grid) {
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
        clear = grid.isAddressable(q) && grid.observed(grid.cellAt(q)) &&
                grid.probability(grid.cellAt(q)) < 0.5;
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

}  // namespace irgs
