#include "core/world/map_file.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/io/atomic_file.hpp"
#include "core/world/ros_map.hpp"
#include "tests/core/io/temp_dir.hpp"

namespace irgs {
namespace {

// A small map that uses every section, including unknown keys at every level.
constexpr const char* kValidMap = R"({
  "format": "irgs-map",
  "version": 1,
  "name": "test room",
  "ceiling_height_m": 2.8,
  "start": {"x": 1.0, "y": 1.5, "theta_rad": 0.5, "x-note": "start"},
  "walls": [
    {"id": "outer", "points": [[0, 0], [4, 0], [4, 3], [0, 3]], "closed": true, "x-colour": "grey"},
    {"id": "stub", "points": [[2, 3], [2, 2.2]]}
  ],
  "obstacles": [
    {"id": "box", "polygon": [[3, 0.5], [3, 1], [3.5, 1], [3.5, 0.5]], "x-height_m": 0.4}
  ],
  "features": [
    {"id": "C0", "kind": "corner", "position": [0, 0]},
    {"id": "E0", "kind": "edge", "position": [2, 2.2]}
  ],
  "ceiling_markers": [
    {"id": "M0", "position": [1, 1], "heading_rad": 0.25, "size_m": 0.2}
  ],
  "ceiling_lights": [
    {"id": "L0", "a": [0.5, 2], "b": [3.5, 2], "width_m": 0.12}
  ],
  "graph": {
    "nodes": [
      {"id": "N0", "position": [1, 1], "marker": "M0"},
      {"id": "N1", "position": [3, 2], "x-action": "stop"}
    ],
    "edges": [{"from": "N0", "to": "N1", "bidirectional": false}],
    "x-planner": {"cost": "length"}
  },
  "x-editor": {"zoom": 2}
})";

MapLoadResult parse(const std::string& text) {
  return parseMapJson(text, "test.json", ".");
}

std::string allDiagnostics(const MapLoadResult& r) {
  std::string out;
  for (const auto& d : r.diagnostics)
    out += d.toString() + "\n";
  return out;
}

// The first error, which a test expects to exist.
Diagnostic firstError(const MapLoadResult& r) {
  for (const auto& d : r.diagnostics) {
    if (d.severity == Severity::kError)
      return d;
  }
  ADD_FAILURE() << "no error in:\n" << allDiagnostics(r);
  return {};
}

// Replaces the first occurrence of `from` in the valid map.
std::string validWith(const std::string& from, const std::string& to) {
  std::string text = kValidMap;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos)
    text.replace(at, from.size(), to);
  return text;
}

TEST(MapFile, LoadsEverySection) {
  const MapLoadResult r = parse(kValidMap);
  ASSERT_TRUE(r.map) << allDiagnostics(r);
  EXPECT_TRUE(r.diagnostics.empty()) << allDiagnostics(r);
  const WorldMap& m = *r.map;
  EXPECT_EQ(m.name, "test room");
  EXPECT_DOUBLE_EQ(m.ceiling_height_m, 2.8);
  EXPECT_EQ(m.start, (Pose2{1.0, 1.5, 0.5}));
  ASSERT_EQ(m.walls.size(), 2U);
  EXPECT_TRUE(m.walls[0].closed);
  EXPECT_EQ(m.walls[0].points.size(), 4U);
  EXPECT_EQ(m.walls[1].points[1], Vec2(2, 2.2));
  ASSERT_EQ(m.obstacles.size(), 1U);
  ASSERT_EQ(m.features.size(), 2U);
  EXPECT_EQ(m.features[1].kind, PointFeatureKind::kEdge);
  ASSERT_EQ(m.markers.size(), 1U);
  EXPECT_DOUBLE_EQ(m.markers[0].heading_rad, 0.25);
  ASSERT_EQ(m.lights.size(), 1U);
  EXPECT_DOUBLE_EQ(m.lights[0].width_m, 0.12);
  ASSERT_EQ(m.graph.nodes.size(), 2U);
  EXPECT_EQ(m.graph.nodes[0].marker_id, "M0");
  ASSERT_EQ(m.graph.edges.size(), 1U);
  EXPECT_FALSE(m.graph.edges[0].bidirectional);
  EXPECT_FALSE(m.raster);
  // 4 outer pieces + 1 stub + 4 obstacle edges
  EXPECT_EQ(m.segments().size(), 9U);
}

TEST(MapFile, ObstaclePolygonsAreStoredCounterClockwise) {
  const MapLoadResult r = parse(kValidMap);  // the box is given clockwise
  ASSERT_TRUE(r.map);
  const auto& poly = r.map->obstacles[0].polygon;
  double area2 = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i)
    area2 += cross(poly[i], poly[(i + 1) % poly.size()]);
  EXPECT_GT(area2, 0.0);
}

TEST(MapFile, UnknownKeysSurviveASaveAndLoadAtEveryLevel) {
  const MapLoadResult r = parse(kValidMap);
  ASSERT_TRUE(r.map);
  const std::string text = serializeMap(*r.map);
  const MapLoadResult again = parse(text);
  ASSERT_TRUE(again.map) << allDiagnostics(again) << text;
  const WorldMap& m = *again.map;
  EXPECT_EQ(m.extra["x-editor"]["zoom"], 2);
  EXPECT_EQ(m.start_extra["x-note"], "start");
  EXPECT_EQ(m.walls[0].extra["x-colour"], "grey");
  EXPECT_EQ(m.obstacles[0].extra["x-height_m"], 0.4);
  EXPECT_EQ(m.graph.nodes[1].extra["x-action"], "stop");
  EXPECT_EQ(m.graph.extra["x-planner"]["cost"], "length");
}

TEST(MapFile, SerializationIsDeterministicAndAFixedPoint) {
  const MapLoadResult r = parse(kValidMap);
  ASSERT_TRUE(r.map);
  const std::string once = serializeMap(*r.map);
  EXPECT_EQ(once, serializeMap(*r.map));
  const MapLoadResult again = parse(once);
  ASSERT_TRUE(again.map);
  EXPECT_EQ(serializeMap(*again.map), once);
  // Fixed key order and readable layout.
  EXPECT_EQ(once.rfind("{\n  \"format\": \"irgs-map\",\n  \"version\": 1,\n", 0), 0U) << once;
  EXPECT_NE(once.find("\"points\": [[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]]"),
            std::string::npos)
      << once;
  EXPECT_EQ(once.back(), '\n');
}

TEST(MapFile, ExactValuesRoundTrip) {
  WorldMap map;
  map.name = "präzise \"quoted\"";
  map.start = {0.1, -1e-7, 3.141592653589793};
  map.walls.push_back({"w", {{0.1 + 0.2, 1.0 / 3.0}, {123456.789, -0.0}}, false, {}});
  const MapLoadResult r = parse(serializeMap(map));
  ASSERT_TRUE(r.map) << allDiagnostics(r);
  EXPECT_EQ(r.map->name, map.name);
  EXPECT_EQ(r.map->start, map.start);
  EXPECT_EQ(r.map->walls[0].points, map.walls[0].points);
}

TEST(MapFile, SaveAndLoadThroughAFile) {
  test::TempDir dir;
  const MapLoadResult r = parse(kValidMap);
  ASSERT_TRUE(r.map);
  ASSERT_EQ(saveMapFile(*r.map, dir / "m.json"), std::nullopt);
  const MapLoadResult loaded = loadMapFile(dir / "m.json");
  ASSERT_TRUE(loaded.map) << allDiagnostics(loaded);
  EXPECT_EQ(serializeMap(*loaded.map), serializeMap(*r.map));
  const MapLoadResult any = loadAnyMap(dir / "m.json");
  EXPECT_TRUE(any.map);
}

TEST(MapFile, NonFiniteValuesRefuseToSerialize) {
  WorldMap map;
  map.walls.push_back({"w", {{0, 0}, {std::nan(""), 1}}, false, {}});
  try {
    (void)serializeMap(map);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/walls/0/points/1/0"), std::string::npos) << e.what();
  }
  test::TempDir dir;
  const auto error = saveMapFile(map, dir / "bad.json");
  ASSERT_TRUE(error);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.json"));
}

TEST(MapFile, SyntaxErrorsNameLineColumnAndField) {
  const std::string text =
      "{\n  \"format\": \"irgs-map\",\n  \"version\": 1,\n"
      "  \"walls\": [{\"points\": [[0, 0] [1, 0]]}]\n}";
  const MapLoadResult r = parse(text);
  EXPECT_FALSE(r.map);
  ASSERT_EQ(r.diagnostics.size(), 1U);
  const Diagnostic& d = r.diagnostics[0];
  EXPECT_EQ(d.file, "test.json");
  EXPECT_EQ(d.line, 4);
  EXPECT_EQ(d.column, 32);
  EXPECT_EQ(d.field, "/walls/0/points/0");
  EXPECT_NE(d.message.find("invalid JSON"), std::string::npos) << d.message;
}

TEST(MapFile, TruncatedAndOverflowingInputIsReported) {
  const MapLoadResult truncated = parse(std::string(kValidMap).substr(0, 300));
  EXPECT_FALSE(truncated.map);
  EXPECT_GT(firstError(truncated).line, 1);
  const MapLoadResult overflow = parse(validWith("\"theta_rad\": 0.5", "\"theta_rad\": 1e999"));
  EXPECT_FALSE(overflow.map);
  const Diagnostic d = firstError(overflow);
  EXPECT_EQ(d.line, 6);
  EXPECT_EQ(d.field, "/start/theta_rad");
  EXPECT_NE(d.message.find("finite"), std::string::npos) << d.message;
  EXPECT_FALSE(parse("").map);
  EXPECT_FALSE(parse("[1, 2]").map);
}

TEST(MapFile, DeepNestingIsRefusedWithoutRecursing) {
  const std::string deep = R"({"format": "irgs-map", "version": 1, "x-deep": )" +
                           std::string(100000, '[') + std::string(100000, ']') + "}";
  const MapLoadResult r = parse(deep);
  EXPECT_FALSE(r.map);
  EXPECT_NE(firstError(r).message.find("nested"), std::string::npos);
}

struct SemanticCase {
  const char* name;
  std::string text;
  const char* field;
  const char* message_part;
  int line;
};

TEST(MapFile, SemanticErrorsNameTheFieldItsLineAndTheReason) {
  const SemanticCase cases[] = {
      {"wrong format", validWith("\"irgs-map\"", "\"other\""), "/format", "not an IRGS map", 2},
      {"newer version", validWith("\"version\": 1", "\"version\": 2"), "/version",
       "unsupported map format version 2", 3},
      {"version as text", validWith("\"version\": 1", "\"version\": \"1\""), "/version", "integer",
       3},
      {"missing version", validWith("\"version\": 1,", ""), "/version", "missing required key", 1},
      {"wall with one point", validWith("[[2, 3], [2, 2.2]]", "[[2, 3]]"), "/walls/1/points",
       "at least 2 points", 9},
      {"closed wall with two points",
       validWith("[[0, 0], [4, 0], [4, 3], [0, 3]]", "[[0, 0], [4, 0]]"), "/walls/0/closed",
       "at least 3 points", 8},
      {"point with three numbers", validWith("[2, 2.2]]", "[2, 2.2, 1]]"), "/walls/1/points/1",
       "[x, y]", 9},
      {"number as string", validWith("[4, 0]", "[\"4\", 0]"), "/walls/0/points/1/0",
       "expected a number, found a string", 8},
      {"polygon with two vertices",
       validWith("[[3, 0.5], [3, 1], [3.5, 1], [3.5, 0.5]]", "[[3, 0.5], [3, 1]]"),
       "/obstacles/0/polygon", "at least 3 vertices", 12},
      {"collinear polygon",
       validWith("[[3, 0.5], [3, 1], [3.5, 1], [3.5, 0.5]]", "[[3, 0.5], [3, 1], [3, 2]]"),
       "/obstacles/0/polygon", "no area", 12},
      {"missing polygon", validWith("\"polygon\"", "\"polygn\""), "/obstacles/0/polygon",
       "missing required key 'polygon'", 12},
      {"duplicate wall id", validWith("\"id\": \"stub\"", "\"id\": \"outer\""), "/walls/1/id",
       "duplicate id 'outer'", 9},
      {"duplicate node id", validWith("\"id\": \"N1\"", "\"id\": \"N0\""), "/graph/nodes/1/id",
       "duplicate id 'N0'", 27},
      {"edge to unknown node", validWith("\"to\": \"N1\"", "\"to\": \"N9\""), "/graph/edges/0/to",
       "unknown node 'N9'", 29},
      {"node with unknown marker", validWith("\"marker\": \"M0\"", "\"marker\": \"M7\""),
       "/graph/nodes/0/marker", "unknown ceiling marker 'M7'", 26},
      {"bad feature kind", validWith("\"kind\": \"edge\"", "\"kind\": \"door\""),
       "/features/1/kind", "\"corner\" or \"edge\"", 16},
      {"negative marker size", validWith("\"size_m\": 0.2", "\"size_m\": -0.2"),
       "/ceiling_markers/0/size_m", "positive", 19},
      {"light of zero length", validWith("\"b\": [3.5, 2]", "\"b\": [0.5, 2]"),
       "/ceiling_lights/0/b", "two different end points", 22},
      {"closed as string", validWith("\"closed\": true", "\"closed\": \"yes\""), "/walls/0/closed",
       "true or false", 8},
      {"walls not an array", validWith("\"walls\": [", "\"walls\": 5, \"w\": ["), "/walls",
       "expected an array", 7},
      {"start without y", validWith("\"y\": 1.5, ", ""), "/start/y", "missing required key 'y'", 6},
      {"missing raster yaml",
       validWith("\"x-editor\"", "\"raster\": {\"source\": \"no.yaml\"}, \"x-e\""),
       "/raster/source", "cannot load the raster layer", 32},
  };
  for (const SemanticCase& c : cases) {
    SCOPED_TRACE(c.name);
    const MapLoadResult r = parse(c.text);
    EXPECT_FALSE(r.map) << "a map with errors must not be returned";
    const Diagnostic d = firstError(r);
    EXPECT_EQ(d.file, "test.json");
    EXPECT_EQ(d.field, c.field) << allDiagnostics(r);
    EXPECT_NE(d.message.find(c.message_part), std::string::npos) << d.message;
    EXPECT_EQ(d.line, c.line) << d.toString();
    EXPECT_GT(d.column, 0);
  }
}

TEST(MapFile, EveryErrorIsReportedNotJustTheFirst) {
  std::string text = validWith("[[2, 3], [2, 2.2]]", "[[2, 3]]");
  text.replace(text.find("\"to\": \"N1\""), 10, "\"to\": \"N9\"");
  const MapLoadResult r = parse(text);
  int errors = 0;
  for (const auto& d : r.diagnostics)
    errors += d.severity == Severity::kError ? 1 : 0;
  EXPECT_EQ(errors, 2) << allDiagnostics(r);
}

TEST(MapFile, WarningsDoNotStopLoading) {
  const MapLoadResult r = parse(validWith("\"closed\": true,", "\"closed\": true, \"colour\": 1,"));
  ASSERT_TRUE(r.map);
  ASSERT_EQ(r.diagnostics.size(), 1U);
  EXPECT_EQ(r.diagnostics[0].severity, Severity::kWarning);
  EXPECT_EQ(r.diagnostics[0].field, "/walls/0/colour");
  EXPECT_EQ(r.map->walls[0].extra["colour"], 1);

  const MapLoadResult inside = parse(validWith("\"x\": 1.0, \"y\": 1.5", "\"x\": 3.2, \"y\": 0.7"));
  ASSERT_TRUE(inside.map);
  ASSERT_FALSE(inside.diagnostics.empty());
  EXPECT_NE(inside.diagnostics[0].message.find("inside obstacle 'box'"), std::string::npos);
}

TEST(MapFile, RasterLayerLoadsRelativeToTheMapFileAndStaysValidWhenSavedElsewhere) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "maps/ros");
  RasterMap raster;
  raster.width = 4;
  raster.height = 3;
  raster.resolution_m = 0.5;
  raster.cells = {0, 0, 100, -1, 0, 0, 0, 0, 100, 100, 0, 0};
  ASSERT_EQ(saveRosMap(raster, dir / "maps/ros/room.yaml"), std::nullopt);
  const std::string text = R"({"format": "irgs-map", "version": 1,
    "raster": {"source": "ros/room.yaml", "x-tint": "blue"}})";
  ASSERT_EQ(writeFileAtomically(dir / "maps/m.json", text), std::nullopt);

  const MapLoadResult r = loadMapFile(dir / "maps/m.json");
  ASSERT_TRUE(r.map) << allDiagnostics(r);
  ASSERT_TRUE(r.map->raster);
  EXPECT_EQ(r.map->raster->source, "ros/room.yaml");
  EXPECT_EQ(r.map->raster->raster.cells, raster.cells);

  // Saved one folder up, the reference is rewritten relative to the new file.
  ASSERT_EQ(saveMapFile(*r.map, dir / "copy.json"), std::nullopt);
  const MapLoadResult copy = loadMapFile(dir / "copy.json");
  ASSERT_TRUE(copy.map) << allDiagnostics(copy);
  EXPECT_EQ(copy.map->raster->source, "maps/ros/room.yaml");
  EXPECT_EQ(copy.map->raster->extra["x-tint"], "blue");
}

TEST(MapFile, LoadAnyMapWrapsARosMapAndRejectsOtherTypes) {
  test::TempDir dir;
  RasterMap raster;
  raster.width = 20;
  raster.height = 20;
  raster.resolution_m = 0.1;
  raster.origin = {-1.0, -1.0, 0.0};
  raster.cells.assign(400, RasterMap::kFree);
  ASSERT_EQ(saveRosMap(raster, dir / "open.yaml"), std::nullopt);
  const MapLoadResult r = loadAnyMap(dir / "open.yaml");
  ASSERT_TRUE(r.map) << allDiagnostics(r);
  EXPECT_EQ(r.map->name, "open");
  ASSERT_TRUE(r.map->raster);
  EXPECT_EQ(r.map->raster->raster.width, 20);

  const MapLoadResult other = loadAnyMap(dir / "map.png");
  EXPECT_FALSE(other.map);
  EXPECT_NE(firstError(other).message.find("unknown map file type"), std::string::npos);
  EXPECT_FALSE(loadAnyMap(dir / "missing.json").map);
}

// Thousands of random byte edits and truncations of a valid file: the loader returns either a
// complete map or errors, never throws or crashes, and every error is located.
TEST(MapFile, RandomMutationsNeverCrashOrHalfLoad) {
  const std::string original = kValidMap;
  std::mt19937 rng(20240601);
  const std::string alphabet = "{}[]:,\"\\0123456789.-+eE tfnrul/xy\n\x80\xff";
  int loaded = 0;
  for (int i = 0; i < 6000; ++i) {
    std::string text = original;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 5) {
        case 0:
          text[at] = alphabet[rng() % alphabet.size()];
          break;
        case 1:
          text.erase(at, 1 + rng() % 8);
          break;
        case 2:
          text.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
        case 3:
          text.resize(at);
          break;
        default:
          text[at] = static_cast<char>(rng() & 0xFF);
          break;
      }
    }
    MapLoadResult r;
    ASSERT_NO_THROW(r = parse(text)) << text;
    ASSERT_EQ(r.map.has_value(), !hasErrors(r.diagnostics)) << allDiagnostics(r);
    for (const Diagnostic& d : r.diagnostics) {
      ASSERT_EQ(d.message.find("internal error"), std::string::npos) << d.toString();
      if (d.severity == Severity::kError && !text.empty()) {
        ASSERT_GT(d.line, 0) << d.toString();
      }
    }
    if (r.map) {
      ++loaded;
      ASSERT_NO_THROW((void)serializeMap(*r.map));
    }
  }
  // Some edits land in harmless places (numbers, strings): both outcomes are exercised.
  EXPECT_GT(loaded, 100);
  EXPECT_LT(loaded, 5000);
}

}  // namespace
}  // namespace irgs
