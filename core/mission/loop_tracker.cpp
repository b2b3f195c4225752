#include "core/mission/loop_tracker.hpp"

#include <cmath>
#include <stdexcept>

#include "core/geometry/geometry_queries.hpp"

namespace irgs {

LoopTracker::LoopTracker(double spacing_m, double closure_radius_m, double min_loop_length_m)
    : spacing_m_(spacing_m),
      closure_radius_m_(closure_radius_m),
      min_loop_length_m_(min_loop_length_m) {
  if (!(spacing_m > 0.0) || !(closure_radius_m > 0.0) || !(min_loop_length_m > closure_radius_m))
    throw std::invalid_argument("LoopTracker: spacing and radius > 0, loop length > radius");
}

void LoopTracker::restart() {
  indices_.clear();
  distance_.clear();
  heading_.clear();
  loop_distance_m_ = 0.0;
}

void LoopTracker::drop(const Pose2& pose) {
  indices_.push_back(pose.position());
  distance_.push_back(loop_distance_m_);
  heading_.push_back(pose.theta);
  all_.push_back(pose.position());
}

std::optional<std::size_t> LoopTracker::onPose(const Pose2& pose, bool following) {
  if (indices_.empty()) {
    if (following) {
      loop_distance_m_ = 0.0;
      drop(pose);
      next_index_at_m_ = spacing_m_;
    }
    last_position_ = pose.position();
    return std::nullopt;
  }
  loop_distance_m_ += (pose.position() - last_position_).norm();
  last_position_ = pose.position();
  if (loop_distance_m_ >= next_index_at_m_) {
    drop(pose);
    next_index_at_m_ += spacing_m_;
  }
  if (!following)
    return std::nullopt;
  for (std::size_t i = 0; i < indices_.size(); ++i) {
    if (loop_distance_m_ - distance_[i] < min_loop_length_m_)
      break;
    if ((pose.position() - indices_[i]).norm() < closure_radius_m_ &&
        std::abs(wrapAngle(pose.theta - heading_[i])) < degToRad(60.0) &&
        std::abs(loopFrom(i, pose.position()).signed_area_m2) >= kMinLoopArea_m2)
      return i;
  }
  return std::nullopt;
}

TracedLoop LoopTracker::loopFrom(std::size_t from, const Vec2& position) const {
  TracedLoop loop;
  loop.indices.assign(indices_.begin() + static_cast<std::ptrdiff_t>(from), indices_.end());
  loop.indices.push_back(position);
  loop.signed_area_m2 = signedArea(loop.indices);
  loop.obstacle = loop.signed_area_m2 > 0.0;
  return loop;
}

}  // namespace irgs
