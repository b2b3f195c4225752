// Checks on the maps shipped in resources/maps/: they load cleanly, their start poses and
// graphs sit in free space, and each paper map has the property it was made for.

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <filesystem>
#include <limits>
#include <map>

#include "core/io/atomic_file.hpp"
#include "core/world/map_file.hpp"
#include "core/world/wall_model.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;

// Half the width of the ~0.3 m robot plus a margin.
constexpr double kRobotRadius_m = 0.2;

fs::path mapsFolder() {
  return fs::path(IRGS_SOURCE_DIR) / "resources" / "maps";
}

WorldMap load(const std::string& name) {
  const MapLoadResult r = loadMapFile(mapsFolder() / name);
  std::string text;
  for (const auto& d : r.diagnostics)
    text += d.toString() + "\n";
  EXPECT_TRUE(r.map) << text;
  return r.map ? *r.map : WorldMap{};
}

double distanceToSegment(const Vec2& p, const Segment& s) {
  const Vec2 d = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (s.a + t * d - p).norm();
}

bool segmentsIntersect(const Segment& s, const Segment& t) {
  const auto orient = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    const double v = cross(b - a, c - a);
    return v > 1e-12 ? 1 : v < -1e-12 ? -1 : 0;
  };
  const int o1 = orient(s.a, s.b, t.a), o2 = orient(s.a, s.b, t.b);
  const int o3 = orient(t.a, t.b, s.a), o4 = orient(t.a, t.b, s.b);
  if (o1 != o2 && o3 != o4)
    return true;
  // Collinear touching counts as well.
  return (o1 == 0 && distanceToSegment(t.a, s) < 1e-12) ||
         (o2 == 0 && distanceToSegment(t.b, s) < 1e-12) ||
         (o3 == 0 && distanceToSegment(s.a, t) < 1e-12) ||
         (o4 == 0 && distanceToSegment(s.b, t) < 1e-12);
}

// Distance along the ray from p in direction heading to the first segment hit, and which.
std::pair<double, std::size_t> castRay(const std::vector<Segment>& segments, const Pose2& p) {
  double best = std::numeric_limits<double>::infinity();
  std::size_t which = segments.size();
  const Vec2 d = p.heading();
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Vec2 e = segments[i].b - segments[i].a;
    const double denom = cross(d, e);
    if (std::abs(denom) < 1e-12)
      continue;
    const Vec2 w = segments[i].a - p.position();
    const double t = cross(w, e) / denom;  // along the ray
    const double u = cross(w, d) / denom;  // along the segment
    if (t > 0 && u >= 0 && u <= 1 && t < best) {
      best = t;
      which = i;
    }
  }
  return {best, which};
}

// Cells (5 cm) reachable from the start by a disc of kRobotRadius_m, by BFS.
class Reachability {
 public:
  explicit Reachability(const WorldMap& map) : map_(map), segments_(map.segments()) {
    const Box2 b = map.bounds();
    origin_ = b.min - Vec2(1, 1);
    w_ = static_cast<int>(std::ceil((b.max.x() - origin_.x() + 1) / kCell));
    h_ = static_cast<int>(std::ceil((b.max.y() - origin_.y() + 1) / kCell));
    reached_.assign(static_cast<std::size_t>(w_ * h_), false);
    std::deque<std::pair<int, int>> queue;
    const auto [c0, r0] = cellOf(map.start.position());
    reached_[index(c0, r0)] = true;
    queue.emplace_back(c0, r0);
    while (!queue.empty()) {
      const auto [c, r] = queue.front();
      queue.pop_front();
      for (const auto& [dc, dr] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int nc = c + dc, nr = r + dr;
        if (nc < 0 || nr < 0 || nc >= w_ || nr >= h_ || reached_[index(nc, nr)] ||
            !free(centre(nc, nr)))
          continue;
        reached_[index(nc, nr)] = true;
        queue.emplace_back(nc, nr);
      }
    }
  }
  bool reached(const Vec2& p) const {
    const auto [c, r] = cellOf(p);
    return reached_[index(c, r)];
  }

 private:
  static constexpr double kCell = 0.05;
  bool free(const Vec2& p) const {
    if (map_.obstacleAt(p) != nullptr)
      return false;
    for (const Segment& s : segments_) {
      if (distanceToSegment(p, s) < kRobotRadius_m)
        return false;
    }
    return true;
  }
  std::pair<int, int> cellOf(const Vec2& p) const {
    return {static_cast<int>((p.x() - origin_.x()) / kCell),
            static_cast<int>((p.y() - origin_.y()) / kCell)};
  }
  Vec2 centre(int c, int r) const { return origin_ + kCell * Vec2(c + 0.5, r + 0.5); }
  std::size_t index(int c, int r) const { return static_cast<std::size_t>(r * w_ + c); }

  const WorldMap& map_;
  std::vector<Segment> segments_;
  Vec2 origin_;
  int w_ = 0, h_ = 0;
  std::vector<bool> reached_;
};

std::vector<std::string> bundledMapNames() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(mapsFolder())) {
    if (entry.path().extension() == ".json")
      names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(BundledMaps, AllBundledMapsArePresent) {
  const std::vector<std::string> expected = {
      "corridor_000_table1.json",        "default.json",
      "delivery_floor_002.json",         "delivery_floor_002_people.json",
      "thesis_arena_250.json",           "thesis_sim1_loop.json",
      "thesis_sim2_four_obstacles.json", "thesis_sim3_five_obstacles.json"};
  EXPECT_EQ(bundledMapNames(), expected);
}

TEST(BundledMaps, EveryMapLoadsWithoutDiagnosticsAndIsInCanonicalForm) {
  for (const std::string& name : bundledMapNames()) {
    SCOPED_TRACE(name);
    const MapLoadResult r = loadMapFile(mapsFolder() / name);
    ASSERT_TRUE(r.map);
    for (const auto& d : r.diagnostics)
      ADD_FAILURE() << d.toString();
    EXPECT_FALSE(r.map->name.empty());
    EXPECT_TRUE(r.map->extra.contains("x-description"));
    // Saving gives the file back byte for byte: the shipped files are what the editor writes.
    EXPECT_EQ(serializeMap(*r.map), readFile(mapsFolder() / name).bytes);
  }
}

TEST(BundledMaps, StartPosesAndGraphNodesAreInFreeSpaceAndConnected) {
  for (const std::string& name : bundledMapNames()) {
    SCOPED_TRACE(name);
    const WorldMap map = load(name);
    const Vec2 start = map.start.position();
    EXPECT_EQ(map.obstacleAt(start), nullptr);
    EXPECT_GE(map.distanceToNearestSegment(start), kRobotRadius_m);
    // Inside every closed outline.
    for (const Wall& w : map.walls) {
      if (!w.closed)
        continue;
      Obstacle as_area{w.id, w.points, {}};
      WorldMap probe;
      probe.obstacles.push_back(as_area);
      EXPECT_NE(probe.obstacleAt(start), nullptr) << "start outside outline " << w.id;
    }
    const Reachability reach(map);
    const auto segments = map.segments();
    for (const TopoNode& n : map.graph.nodes) {
      EXPECT_EQ(map.obstacleAt(n.position), nullptr) << n.id;
      EXPECT_GE(map.distanceToNearestSegment(n.position), kRobotRadius_m) << n.id;
      EXPECT_TRUE(reach.reached(n.position)) << "node " << n.id << " cannot be reached";
    }
    std::map<std::string, Vec2> nodes;
    for (const TopoNode& n : map.graph.nodes)
      nodes[n.id] = n.position;
    for (const TopoEdge& e : map.graph.edges) {
      const Segment edge{nodes.at(e.from), nodes.at(e.to)};
      for (const Segment& s : segments)
        EXPECT_FALSE(segmentsIntersect(edge, s)) << "edge " << e.from << "-" << e.to;
    }
  }
}

TEST(BundledMaps, DeliveryFloorHasMarkersAtNodesLightsAlongEdgesAndATAndAnLJunction) {
  for (const char* name : {"delivery_floor_002.json", "delivery_floor_002_people.json"}) {
    SCOPED_TRACE(name);
    const WorldMap map = load(name);
    ASSERT_EQ(map.graph.nodes.size(), 7u);
    std::map<std::string, Vec2> markers, nodes;
    for (const CeilingMarker& m : map.markers)
      markers[m.id] = m.position;
    std::map<std::string, int> degree;
    for (const TopoNode& n : map.graph.nodes) {
      nodes[n.id] = n.position;
      ASSERT_FALSE(n.marker_id.empty()) << n.id;
      EXPECT_LT((markers.at(n.marker_id) - n.position).norm(), 1e-9) << n.id;
    }
    for (const TopoEdge& e : map.graph.edges) {
      ++degree[e.from];
      ++degree[e.to];
    }
    EXPECT_EQ(degree["1"], 3);  // T junctions
    EXPECT_EQ(degree["4"], 3);
    EXPECT_EQ(degree["2"], 2);  // L junctions
    EXPECT_EQ(degree["3"], 2);
    EXPECT_EQ(degree["0"], 1);  // start and goal are dead ends
    EXPECT_EQ(degree["6"], 1);
    // Every light lies on an edge (a light row) and every edge has lights.
    std::map<std::pair<std::string, std::string>, int> lit;
    for (const CeilingLight& l : map.lights) {
      bool on_edge = false;
      for (const TopoEdge& e : map.graph.edges) {
        const Vec2 a = nodes.at(e.from), b = nodes.at(e.to);
        if (distanceToSegment(l.tube.a, Segment{a, b}) < 1e-6 &&
            distanceToSegment(l.tube.b, Segment{a, b}) < 1e-6) {
          on_edge = true;
          ++lit[{e.from, e.to}];
        }
      }
      EXPECT_TRUE(on_edge) << l.id;
    }
    EXPECT_EQ(lit.size(), map.graph.edges.size());
  }
  const WorldMap people = load("delivery_floor_002_people.json");
  ASSERT_EQ(people.moving_obstacles.size(), 3u);
  for (const MovingObstacle& m : people.moving_obstacles) {
    for (const Vec2& p : m.path)
      EXPECT_GE(people.distanceToNearestSegment(p), 0.3) << m.id;
  }
}

TEST(BundledMaps, DefaultApartmentHasRoomsObstaclesAndLandmarks) {
  const WorldMap map = load("default.json");
  const Vec2 size = map.bounds().size();
  EXPECT_NEAR(size.x(), 8.0, 1e-9);
  EXPECT_NEAR(size.y(), 6.0, 1e-9);
  EXPECT_GE(map.obstacles.size(), 4U);
  EXPECT_GE(map.features.size(), 4U);
  EXPECT_GE(map.markers.size(), 3U);
  EXPECT_GE(map.lights.size(), 3U);
  EXPECT_GE(map.graph.nodes.size(), 5U);
  // Every room (its graph node) is reachable: the doorways are wide enough for the robot.
  const Reachability reach(map);
  for (const TopoNode& n : map.graph.nodes)
    EXPECT_TRUE(reach.reached(n.position)) << n.id;
}

TEST(BundledMaps, Simulation1IsOneClosedOutlineWithRightAnglesOnly) {
  const WorldMap map = load("thesis_sim1_loop.json");
  EXPECT_TRUE(map.obstacles.empty());
  ASSERT_EQ(map.walls.size(), 1U);
  const Wall& w = map.walls[0];
  EXPECT_TRUE(w.closed);
  const std::size_t n = w.points.size();
  EXPECT_GT(n, 4U) << "more than one rectangle";
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 in = w.points[i] - w.points[(i + n - 1) % n];
    const Vec2 out = w.points[(i + 1) % n] - w.points[i];
    EXPECT_NEAR(in.dot(out), 0.0, 1e-12) << "corner " << i << " is not 90 degrees";
  }
}

TEST(BundledMaps, Simulation2RobotMeetsTheWallFirst) {
  const WorldMap map = load("thesis_sim2_four_obstacles.json");
  EXPECT_EQ(map.obstacles.size(), 4U);
  const auto segments = map.segments();  // wall pieces come first
  const auto [distance, which] = castRay(segments, map.start);
  EXPECT_LT(which, 4U) << "the first surface ahead is a wall";
  double nearest_obstacle = std::numeric_limits<double>::infinity();
  for (std::size_t i = 4; i < segments.size(); ++i)
    nearest_obstacle =
        std::min(nearest_obstacle, distanceToSegment(map.start.position(), segments[i]));
  EXPECT_LT(distance, nearest_obstacle);
}

TEST(BundledMaps, Simulation3RobotMeetsAnObstacleFirst) {
  const WorldMap map = load("thesis_sim3_five_obstacles.json");
  EXPECT_EQ(map.obstacles.size(), 5U);
  const auto segments = map.segments();
  const std::size_t wall_pieces = 4;
  const auto [distance, which] = castRay(segments, map.start);
  EXPECT_GE(which, wall_pieces) << "the first surface ahead must be an obstacle";
  // It is also the nearest surface in any direction.
  double nearest_wall = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < wall_pieces; ++i)
    nearest_wall = std::min(nearest_wall, distanceToSegment(map.start.position(), segments[i]));
  EXPECT_NEAR(map.distanceToNearestSegment(map.start.position()), distance, 1e-12);
  EXPECT_LT(distance, nearest_wall);
}

TEST(BundledMaps, ArenaIs250cmWith45And90DegreeCornersAndABox) {
  const WorldMap map = load("thesis_arena_250.json");
  const Vec2 size = map.bounds().size();
  EXPECT_NEAR(size.x(), 2.5, 1e-9);
  EXPECT_NEAR(size.y(), 2.5, 1e-9);
  ASSERT_EQ(map.obstacles.size(), 1U);
  ASSERT_EQ(map.walls.size(), 1U);
  const auto& pts = map.walls[0].points;
  int right = 0, oblique = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec2 in = (pts[i] - pts[(i + pts.size() - 1) % pts.size()]).normalized();
    const Vec2 out = (pts[(i + 1) % pts.size()] - pts[i]).normalized();
    const double turn_deg = radToDeg(std::acos(std::clamp(in.dot(out), -1.0, 1.0)));
    right += std::abs(turn_deg - 90.0) < 1e-6 ? 1 : 0;
    oblique += std::abs(turn_deg - 45.0) < 1e-6 ? 1 : 0;
  }
  EXPECT_GE(right, 1);
  EXPECT_GE(oblique, 2);
  EXPECT_EQ(right + oblique, static_cast<int>(pts.size()));
}

// Reads the (P_R, phi, P_V) stored beside each wall of the corridor map.
WallLine claimed(const nlohmann::json& j) {
  return {j.at("p_r_m").get<double>(), degToRad(j.at("phi_deg").get<double>()),
          j.at("p_v").get<int>()};
}

TEST(BundledMaps, CorridorWallModelReproducesTheClaimedTable1Values) {
  const WorldMap map = load("corridor_000_table1.json");
  int table_walls = 0;
  for (const Wall& w : map.walls) {
    SCOPED_TRACE(w.id);
    ASSERT_EQ(w.points.size(), 2U);
    // Each segment runs with the corridor on its left: that face is the one the robot sees.
    const Segment s{w.points[0], w.points[1]};
    const WallLine derived = wallLineFromFace(s, s.leftNormal());
    const WallLine claim = claimed(w.extra.at("x-wall_model"));
    EXPECT_NEAR(derived.p_r_m, claim.p_r_m, 1e-9);
    EXPECT_NEAR(wrapAngle(derived.phi_rad - claim.phi_rad), 0.0, 1e-9);
    EXPECT_EQ(derived.p_v, claim.p_v);
    if (!w.extra.contains("x-table1_printed"))
      continue;
    ++table_walls;
    // Against the printed row, read axis-aligned (A000-8): 11 -> 0, 191 -> 180, 281 -> 270.
    const WallLine printed = claimed(w.extra.at("x-table1_printed"));
    const double axis_phi = degToRad(90.0 * std::round(radToDeg(printed.phi_rad) / 90.0));
    EXPECT_NEAR(derived.p_r_m, printed.p_r_m, 1e-9);
    EXPECT_NEAR(wrapAngle(derived.phi_rad - axis_phi), 0.0, 1e-9);
    EXPECT_EQ(derived.p_v, printed.p_v);
  }
  EXPECT_EQ(table_walls, 10);
  ASSERT_TRUE(map.extra.contains("x-table1_verbatim"));
  EXPECT_EQ(map.extra["x-table1_verbatim"]["walls"].size(), 10U);
  EXPECT_EQ(map.extra["x-table1_verbatim"]["corners"].size(), 8U);
}

TEST(BundledMaps, CorridorCornersAndEdgesAreWallIntersections) {
  const WorldMap map = load("corridor_000_table1.json");
  const auto segments = map.segments();
  int corners = 0;
  for (const PointFeature& f : map.features) {
    int touching = 0;
    for (const Segment& s : segments)
      touching += distanceToSegment(f.position, s) < 1e-9 ? 1 : 0;
    EXPECT_EQ(touching, 2) << f.id;
    corners += f.kind == PointFeatureKind::kCorner ? 1 : 0;
  }
  EXPECT_EQ(corners, 8);  // C0..C7 as in Table 1
  // A robot in the corridor sees each face from the side the model says (predicted d > 0).
  for (const Wall& w : map.walls) {
    const Segment s{w.points[0], w.points[1]};
    const WallLine line = wallLineFromFace(s, s.leftNormal());
    const Vec2 mid = 0.5 * (s.a + s.b) + 0.3 * s.leftNormal();
    EXPECT_NEAR(predictedWallDistance(line, {mid.x(), mid.y(), 0.0}), 0.3, 1e-9) << w.id;
  }
}

}  // namespace
}  // namespace irgs
