#pragma once
// Position indices along a followed wall and the closed-loop check of the thesis (003_…,
// Fig. 3.7; digest 4.5): while the robot follows a surface an index is dropped every
// spacing_m of path; the loop is closed when the robot is back within closure_radius_m of an
// earlier index of the same loop, heading within 60 degrees of the way it passed there, after
// at least min_loop_length_m of loop, around some area: a path that came back on itself (the
// follower lost the wall and turned back along it) encloses nothing and closes no loop. Host
// side, in the map frame.

#include <cstddef>
#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/mission/map_building_config.hpp"

namespace irgs {

class LoopTracker {
 public:
  // Smaller than any surface followed at the usual 0.3 m (a 10 cm post gives ~0.4 m2).
  static constexpr double kMinLoopArea_m2 = 0.2;

  LoopTracker(double spacing_m, double closure_radius_m, double min_loop_length_m);

  // Forgets the current loop (a new surface is being followed).
  void restart();
  // One pose of the robot. Indices start with the first pose at which `following` holds;
  // closure is checked only while following. Returns the index the loop closed at.
  std::optional<std::size_t> onPose(const Pose2& pose, bool following);
  // The loop from index `from` through the current position: signed area and orientation.
  TracedLoop loopFrom(std::size_t from, const Vec2& position) const;

  bool started() const { return !indices_.empty(); }
  const std::vector<Vec2>& indices() const { return indices_; }  // of the current loop
  const std::vector<Vec2>& allIndices() const { return all_; }   // every index of the run
  double loopDistance_m() const { return loop_distance_m_; }

 private:
  void drop(const Pose2& pose);

  double spacing_m_;
  double closure_radius_m_;
  double min_loop_length_m_;
  std::vector<Vec2> indices_;
  std::vector<double> distance_;  // loop path length at each index
  std::vector<double> heading_;
  std::vector<Vec2> all_;
  double loop_distance_m_ = 0.0;
  double next_index_at_m_ = 0.0;
  Vec2 last_position_ = Vec2::Zero();
};

}  // namespace irgs
