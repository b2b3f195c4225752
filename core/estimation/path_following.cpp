#include "core/estimation/path_following.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/motion/path_law.hpp"
#include "core/sim/diff_drive.hpp"

namespace irgs {

namespace {

bool finitePose(const Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

Vec2 leftNormalOf(double heading_rad) {
  return {-std::sin(heading_rad), std::cos(heading_rad)};
}

}  // namespace

ReferencePath::ReferencePath(const Pose2& start) {
  if (!finitePose(start))
    throw std::invalid_argument("ReferencePath: non-finite start pose");
  start_ = {start.x, start.y, wrapAngle(start.theta)};
  end_ = start_;
}

void ReferencePath::append(double length_m, double curvature) {
  Piece piece;
  piece.start = end_;
  piece.s0_m = length_m_;
  piece.length_m = length_m;
  piece.curvature = curvature;
  pieces_.push_back(piece);
  length_m_ += length_m;
  end_ = pointOn(piece, length_m).pose;
}

ReferencePath& ReferencePath::addLine(double length_m) {
  if (!std::isfinite(length_m) || !(length_m > 0.0))
    throw std::invalid_argument("ReferencePath::addLine: length must be finite and > 0");
  append(length_m, 0.0);
  return *this;
}

ReferencePath& ReferencePath::addArc(double radius_m, double angle_rad) {
  if (!std::isfinite(radius_m) || !(radius_m > 0.0) || !std::isfinite(angle_rad) ||
      angle_rad == 0.0 || std::abs(angle_rad) > 2.0 * kPi)
    throw std::invalid_argument(
        "ReferencePath::addArc: radius must be finite and > 0, angle finite, non-zero and at "
        "most one full turn");
  const double sign = angle_rad > 0.0 ? 1.0 : -1.0;
  append(radius_m * std::abs(angle_rad), sign / radius_m);
  return *this;
}

ReferencePath::Point ReferencePath::pointOn(const Piece& piece, double t_m) const {
  // Constant curvature: the exact arc (a line when c = 0).
  return {piece.s0_m + t_m, integrateArc(piece.start, t_m, piece.curvature * t_m), piece.curvature};
}

ReferencePath::Point ReferencePath::at(double s_m) const {
  if (pieces_.empty())
    return {0.0, start_, 0.0};
  const double s = std::clamp(std::isfinite(s_m) ? s_m : 0.0, 0.0, length_m_);
  for (const Piece& piece : pieces_) {
    if (s <= piece.s0_m + piece.length_m)
      return pointOn(piece, s - piece.s0_m);
  }
  return pointOn(pieces_.back(), pieces_.back().length_m);
}

ReferencePath::Projection ReferencePath::project(const Vec2& p, double s_min_m,
                                                 double s_max_m) const {
  Projection best;
  best.point = at(0.0);
  best.lateral_m = (p - best.point.pose.position()).dot(leftNormalOf(best.point.pose.theta));
  if (pieces_.empty() || !p.allFinite())
    return best;
  double lo = std::clamp(std::isfinite(s_min_m) ? s_min_m : 0.0, 0.0, length_m_);
  double hi = std::clamp(std::isfinite(s_max_m) ? s_max_m : length_m_, 0.0, length_m_);
  if (lo > hi)
    std::swap(lo, hi);
  double best_dist = std::numeric_limits<double>::infinity();
  for (const Piece& piece : pieces_) {
    const double t_lo = std::max(0.0, lo - piece.s0_m);
    const double t_hi = std::min(piece.length_m, hi - piece.s0_m);
    if (t_lo > t_hi)
      continue;  // piece outside the window
    double t = 0.0;
    const Vec2 a = piece.start.position();
    if (piece.curvature == 0.0) {
      t = (p - a).dot(piece.start.heading());
    } else {
      const double k = piece.curvature;
      const Vec2 centre = a + leftNormalOf(piece.start.theta) / k;
      const Vec2 u0 = a - centre, u = p - centre;
      if (u.norm() > 1e-12) {
        // Angle swept from the start in the direction of travel, in [0, 2 pi).
        double delta = std::atan2(cross(u0, u), u0.dot(u)) * (k > 0.0 ? 1.0 : -1.0);
        if (delta < 0.0)
          delta += 2.0 * kPi;
        t = delta / std::abs(k);
        if (t > piece.length_m) {
          // Beyond the arc's end: the nearer endpoint.
          const Vec2 end = pointOn(piece, piece.length_m).pose.position();
          t = (p - end).norm() < (p - a).norm() ? piece.length_m : 0.0;
        }
      }
    }
    t = std::clamp(t, t_lo, t_hi);
    const Point q = pointOn(piece, t);
    const double dist = (p - q.pose.position()).norm();
    if (dist < best_dist) {
      best_dist = dist;
      best.point = q;
    }
  }
  best.lateral_m = (p - best.point.pose.position()).dot(leftNormalOf(best.point.pose.theta));
  return best;
}

std::vector<ReferencePath::Point> ReferencePath::sample(double step_m) const {
  if (!std::isfinite(step_m) || !(step_m > 0.0))
    throw std::invalid_argument("ReferencePath::sample: step must be finite and > 0");
  std::vector<Point> out;
  for (double s = 0.0; s < length_m_; s += step_m)
    out.push_back(at(s));
  out.push_back(at(length_m_));
  return out;
}

void validate(const PathFollowerConfig& c) {
  for (double v : {c.speed_mps, c.k2, c.k3, c.max_turn_rate_radps, c.min_denominator,
                   c.search_back_m, c.search_ahead_m}) {
    if (!std::isfinite(v) || !(v > 0.0))
      throw std::invalid_argument(
          "PathFollowerConfig: speed, gains, turn rate, min_denominator and the search window "
          "must be finite and > 0");
  }
  if (c.min_denominator >= 1.0)
    throw std::invalid_argument("PathFollowerConfig: min_denominator must be < 1");
}

const char* toString(PathFollowStatus status) {
  switch (status) {
    case PathFollowStatus::kFollowing:
      return "following";
    case PathFollowStatus::kReachedEnd:
      return "reached the end";
    case PathFollowStatus::kSingular:
      return "singular: 1 - c l too small";
    case PathFollowStatus::kInvalidInput:
      return "invalid input";
  }
  return "unknown";
}

PathFollower::PathFollower(ReferencePath path, PathFollowerConfig config)
    : path_(std::move(path)), config_(config) {
  validate(config_);
  if (path_.empty())
    throw std::invalid_argument("PathFollower: the path is empty");
}

PathFollowOutput PathFollower::update(const Pose2& pose) {
  PathFollowOutput out;
  if (!finitePose(pose))
    return out;  // kInvalidInput, zero command
  const ReferencePath::Projection proj =
      path_.project(pose.position(), s_m_ - config_.search_back_m, s_m_ + config_.search_ahead_m);
  s_m_ = proj.point.s_m;
  out.s_m = proj.point.s_m;
  out.lateral_m = proj.lateral_m;
  out.curvature = proj.point.curvature;
  const double theta_r = proj.point.pose.theta;
  out.heading_error_rad = wrapAngle(pose.theta - theta_r);

  const Pose2 end = path_.end();
  if (out.s_m >= path_.length_m() - 1e-9 &&
      (pose.position() - end.position()).dot(end.heading()) >= 0.0) {
    out.status = PathFollowStatus::kReachedEnd;
    return out;
  }
  const double l = out.lateral_m, c = out.curvature, e = out.heading_error_rad;
  const double denominator = 1.0 - c * l;
  if (denominator < config_.min_denominator) {
    out.status = PathFollowStatus::kSingular;
    return out;
  }
  const double v = config_.speed_mps;
  // (22) and (25): feed-forward of the path's turn, then lateral and heading terms.
  const motion::PathLawOutput law = motion::pathFollowingLaw(v, l, e, c, config_.k2, config_.k3);
  out.sdot_mps = law.sdot_mps;
  const double omega = law.omega_radps;
  out.command = {v, std::clamp(omega, -config_.max_turn_rate_radps, config_.max_turn_rate_radps)};
  out.status = PathFollowStatus::kFollowing;
  return out;
}

}  // namespace irgs
