#include "core/world/moving_obstacle.hpp"

#include <gtest/gtest.h>

#include "core/world/map_file.hpp"

namespace irgs {
namespace {

// Line 9 holds the moving obstacle's object.
constexpr const char* kMap = R"({
  "format": "irgs-map",
  "version": 1,
  "name": "movers",
  "start": {"x": 1.0, "y": 1.0},
  "walls": [{"points": [[0, 0], [6, 0], [6, 4], [0, 4]], "closed": true}],
  "moving_obstacles": [
    {"id": "p1",
     "polygon": [[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]],
     "path": [[1, 3], [5, 3]], "speed_mps": 0.5, "loop": true, "start_delay_s": 2}
  ]
})";

std::string with(const std::string& from, const std::string& to) {
  std::string text = kMap;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

MovingObstacle backAndForth(bool loop) {
  MovingObstacle m;
  m.path = {Vec2(0, 0), Vec2(4, 0)};
  m.speed_mps = 1.0;
  m.loop = loop;
  m.start_delay_s = 1.0;
  m.polygon = {Vec2(-0.1, -0.1), Vec2(0.1, -0.1), Vec2(0.1, 0.1)};
  return m;
}

TEST(MovingObstacle, TwoPointLoopGoesBackAndForthAfterTheDelay) {
  const MovingObstacle m = backAndForth(true);
  EXPECT_DOUBLE_EQ(movingObstaclePathLength(m), 8.0);
  EXPECT_EQ(movingObstaclePosition(m, 0.5), Vec2(0, 0));
  EXPECT_TRUE(movingObstaclePosition(m, 3.0).isApprox(Vec2(2, 0)));
  EXPECT_TRUE(movingObstaclePosition(m, 7.0).isApprox(Vec2(2, 0)));  // on the way back
  EXPECT_TRUE(movingObstaclePosition(m, 9.5).isApprox(Vec2(0.5, 0)));
}

TEST(MovingObstacle, WithoutLoopItStopsAtTheLastPoint) {
  const MovingObstacle m = backAndForth(false);
  EXPECT_DOUBLE_EQ(movingObstaclePathLength(m), 4.0);
  EXPECT_TRUE(movingObstaclePosition(m, 100.0).isApprox(Vec2(4, 0)));
  EXPECT_TRUE(movingObstaclePolygon(m, Vec2(1, 1))[1].isApprox(Vec2(1.1, 0.9)));
}

TEST(MovingObstacle, LoadsAndSavesWithTheMapFile) {
  const MapLoadResult r = parseMapJson(kMap, "movers.json", ".");
  ASSERT_TRUE(r.map);
  EXPECT_TRUE(r.diagnostics.empty());
  ASSERT_EQ(r.map->moving_obstacles.size(), 1u);
  const MovingObstacle& m = r.map->moving_obstacles[0];
  EXPECT_EQ(m.id, "p1");
  EXPECT_EQ(m.path.size(), 2u);
  EXPECT_DOUBLE_EQ(m.speed_mps, 0.5);
  EXPECT_DOUBLE_EQ(m.start_delay_s, 2.0);
  const std::string saved = serializeMap(*r.map);
  EXPECT_NE(saved.find("\"moving_obstacles\""), std::string::npos);
  const MapLoadResult again = parseMapJson(saved, "again.json", ".");
  ASSERT_TRUE(again.map);
  EXPECT_EQ(serializeMap(*again.map), saved);
  // A map without the layer does not grow the key.
  WorldMap plain = *r.map;
  plain.moving_obstacles.clear();
  EXPECT_EQ(serializeMap(plain).find("moving_obstacles"), std::string::npos);
}

struct BadCase {
  const char* what;
  std::string text;
  const char* field;
  const char* message;
  int line;
};

TEST(MovingObstacle, MalformedEntriesNameTheFieldAndTheLine) {
  const BadCase cases[] = {
      {"no path", with("\"path\": [[1, 3], [5, 3]], ", ""), "/moving_obstacles/0/path",
       "missing required key 'path'", 8},
      {"empty path", with("[[1, 3], [5, 3]]", "[]"), "/moving_obstacles/0/path",
       "at least 1 waypoint", 10},
      {"negative speed", with("\"speed_mps\": 0.5", "\"speed_mps\": -1"),
       "/moving_obstacles/0/speed_mps", "positive number", 10},
      {"loop as text", with("\"loop\": true", "\"loop\": \"yes\""), "/moving_obstacles/0/loop", "",
       10},
      {"negative delay", with("\"start_delay_s\": 2", "\"start_delay_s\": -2"),
       "/moving_obstacles/0/start_delay_s", ">= 0", 10},
      {"flat polygon",
       with("[[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2], [-0.2, 0.2]]", "[[0, 0], [1, 0], [2, 0]]"),
       "/moving_obstacles/0/polygon", "no area", 9},
      {"waypoint as text", with("[5, 3]", "\"5, 3\""), "/moving_obstacles/0/path/1", "", 10},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.what);
    const MapLoadResult r = parseMapJson(c.text, "movers.json", ".");
    EXPECT_FALSE(r.map);
    ASSERT_FALSE(r.diagnostics.empty());
    const Diagnostic& d = r.diagnostics.front();
    EXPECT_EQ(d.severity, Severity::kError);
    EXPECT_EQ(d.field, c.field);
    EXPECT_NE(d.message.find(c.message), std::string::npos) << d.message;
    EXPECT_EQ(d.line, c.line) << d.toString();
  }
}

TEST(MovingObstacle, UnknownKeysWarnAndAreKept) {
  const MapLoadResult r =
      parseMapJson(with("\"loop\": true", "\"loop\": true, \"sped\": 1"), "movers.json", ".");
  ASSERT_TRUE(r.map);
  ASSERT_EQ(r.diagnostics.size(), 1u);
  EXPECT_EQ(r.diagnostics[0].severity, Severity::kWarning);
  EXPECT_TRUE(r.map->moving_obstacles[0].extra.contains("sped"));
}

}  // namespace
}  // namespace irgs
