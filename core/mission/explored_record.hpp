#pragma once
// What map building has explained so far, in the map frame: the room's outline, the obstacles
// circumnavigated, the pockets and fragments traced along them, the spots given up on
// (blacklist) and where every obstacle loop began. The interior target search asks it whether
// a point still needs a visit.

#include <optional>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/mission/map_building_config.hpp"

namespace irgs {

class ExploredRecord {
 public:
  // `margin_m`: a point this close to a traced loop is explained by it (the follower's distance
  // plus the reach of its side sonars).
  explicit ExploredRecord(double margin_m) : margin_m_(margin_m) {}

  void setOutline(TracedLoop loop) { outline_ = std::move(loop); }
  void addObstacle(TracedLoop loop) { obstacles_.push_back(std::move(loop)); }
  void addPocket(TracedLoop loop) { pockets_.push_back(std::move(loop)); }
  void blacklist(const Vec2& p, double radius_m) { blacklist_.push_back({p, radius_m}); }
  void addObstacleAnchor(const Vec2& p) { anchors_.push_back(p); }

  const std::optional<TracedLoop>& outline() const { return outline_; }
  const std::vector<TracedLoop>& obstacles() const { return obstacles_; }
  // Inside the outline (false before it is closed).
  bool insideOutline(const Vec2& p) const;
  // Near the outline, inside or near an obstacle loop, or near a pocket.
  bool explained(const Vec2& p) const;
  bool nearOutline(const Vec2& p, double distance_m) const;
  // On a blacklisted spot.
  bool listed(const Vec2& p) const;
  // Obstacles packed closer than the follower's reach (a post in a narrow aisle between boxes)
  // merge into loops round several of them, pockets and fragments; after kMaxLoopsNearSpot
  // loops started within kRevisitRadius_m of a spot, what is left there has been seen from
  // close by and is mapped, not circled.
  bool visitedOften(const Vec2& p) const;

  static constexpr double kRevisitRadius_m = 1.0;
  static constexpr int kMaxLoopsNearSpot = 2;

 private:
  struct Spot {
    Vec2 centre;
    double radius_m;
  };
  double margin_m_;
  std::optional<TracedLoop> outline_;
  std::vector<TracedLoop> obstacles_;
  std::vector<TracedLoop> pockets_;
  std::vector<Spot> blacklist_;
  std::vector<Vec2> anchors_;
};

}  // namespace irgs
