#include "core/estimation/trajectory_compare.hpp"

#include <algorithm>
#include <cmath>

namespace irgs {
namespace {

bool finitePose(const Pose2& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta);
}

}  // namespace

bool interpolatePose(const std::vector<TimedPose>& b, double t_s, Pose2& out) {
  if (b.empty() || !std::isfinite(t_s) || t_s < b.front().t_s || t_s > b.back().t_s)
    return false;
  // First pose at or after t.
  const auto hi = std::lower_bound(b.begin(), b.end(), t_s,
                                   [](const TimedPose& p, double t) { return p.t_s < t; });
  if (hi == b.begin() || hi->t_s == t_s) {
    out = hi->pose;
    return true;
  }
  const auto lo = hi - 1;
  const double span = hi->t_s - lo->t_s;
  const double f = span > 0.0 ? (t_s - lo->t_s) / span : 0.0;
  out.x = lo->pose.x + f * (hi->pose.x - lo->pose.x);
  out.y = lo->pose.y + f * (hi->pose.y - lo->pose.y);
  out.theta = wrapAngle(lo->pose.theta + f * wrapAngle(hi->pose.theta - lo->pose.theta));
  return true;
}

TrajectoryDifference compareTrajectories(const std::vector<TimedPose>& a,
                                         const std::vector<TimedPose>& b) {
  TrajectoryDifference d;
  double sum_sq_pos = 0.0;
  double sum_sq_heading = 0.0;
  for (const TimedPose& p : a) {
    Pose2 q;
    if (!finitePose(p.pose) || !interpolatePose(b, p.t_s, q) || !finitePose(q))
      continue;
    const double dp = std::hypot(p.pose.x - q.x, p.pose.y - q.y);
    const double dh = std::abs(wrapAngle(p.pose.theta - q.theta));
    ++d.compared;
    sum_sq_pos += dp * dp;
    sum_sq_heading += dh * dh;
    d.max_position_m = std::max(d.max_position_m, dp);
    d.max_heading_rad = std::max(d.max_heading_rad, dh);
    d.final_position_m = dp;
    d.final_heading_rad = dh;
  }
  if (d.compared > 0) {
    d.rms_position_m = std::sqrt(sum_sq_pos / static_cast<double>(d.compared));
    d.rms_heading_rad = std::sqrt(sum_sq_heading / static_cast<double>(d.compared));
  }
  return d;
}

}  // namespace irgs
