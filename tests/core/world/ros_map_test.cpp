#include "core/world/ros_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <random>

#include "core/io/atomic_file.hpp"
#include "tests/core/io/temp_dir.hpp"

namespace irgs {
namespace {

namespace fs = std::filesystem;

std::string allDiagnostics(const RosMapLoadResult& r) {
  std::string out;
  for (const auto& d : r.diagnostics)
    out += d.toString() + "\n";
  return out;
}

Diagnostic firstError(const RosMapLoadResult& r) {
  for (const auto& d : r.diagnostics) {
    if (d.severity == Severity::kError)
      return d;
  }
  ADD_FAILURE() << "no error in:\n" << allDiagnostics(r);
  return {};
}

// One image row of six pixels, two rows; the bottom image row is raster row 0.
GrayImage testImage() {
  return {6,
          2,
          {254, 0, 205, 100, 50, 128,  // top
           255, 255, 255, 255, 255, 37}};
}

TEST(RosMap, TrinaryPixelsFollowTheThresholdsAndTheImageIsFlipped) {
  RosMapMetadata m;  // occupied 0.65, free 0.196
  m.resolution_m = 0.5;
  m.origin = {-1, -2, 0};
  const RasterMap r = rasterFromImage(testImage(), m);
  EXPECT_EQ(r.width, 6);
  EXPECT_EQ(r.height, 2);
  EXPECT_EQ(r.resolution_m, 0.5);
  EXPECT_EQ(r.origin, (Pose2{-1, -2, 0}));
  // Raster row 1 is the image's top row: occ = 1 - p/255.
  // 254 -> 0.004 free, 0 -> 1 occupied, 205 -> 0.196 unknown, 100 -> 0.61 unknown,
  // 50 -> 0.80 occupied, 128 -> 0.50 unknown.
  EXPECT_EQ(std::vector<std::int8_t>(r.cells.begin() + 6, r.cells.end()),
            (std::vector<std::int8_t>{0, 100, -1, -1, 100, -1}));
  EXPECT_EQ(r.at(5, 0), 100);  // 37 -> 0.85
  EXPECT_EQ(r.at(0, 0), 0);
}

TEST(RosMap, NegateScaleAndRawModes) {
  RosMapMetadata m;
  m.negate = true;  // occ = p / 255: black is free
  RasterMap r = rasterFromImage(testImage(), m);
  EXPECT_EQ(r.at(1, 1), 0);    // pixel 0
  EXPECT_EQ(r.at(0, 1), 100);  // pixel 254

  m = {};
  m.mode = RosMapMode::kScale;
  r = rasterFromImage(testImage(), m);
  // 128: occ = 0.49804, rint(100 * (0.49804 - 0.196) / 0.454) = rint(66.53) = 67
  EXPECT_EQ(r.at(5, 1), 67);
  // 100: occ = 0.60784 -> rint(90.71) = 91
  EXPECT_EQ(r.at(3, 1), 91);
  EXPECT_EQ(r.at(1, 1), 100);
  EXPECT_EQ(r.at(0, 1), 0);

  m.mode = RosMapMode::kRaw;
  r = rasterFromImage(testImage(), m);
  EXPECT_EQ(r.at(5, 0), 37);
  EXPECT_EQ(r.at(4, 1), 50);
  EXPECT_EQ(r.at(0, 0), -1);  // 255 > 100
  EXPECT_EQ(r.at(3, 1), 100);
}

RasterMap randomRaster(std::mt19937& rng, bool with_unknown, bool with_levels) {
  RasterMap r;
  r.width = 37;
  r.height = 23;
  r.resolution_m = 0.05;
  r.origin = {-1.25, 3.5, 0.0};
  for (int i = 0; i < r.width * r.height; ++i) {
    const auto pick = static_cast<unsigned>(rng() % 3);
    std::int8_t v = pick == 0 ? RasterMap::kFree : pick == 1 ? RasterMap::kOccupied : -1;
    if (v == -1 && !with_unknown)
      v = RasterMap::kFree;
    if (with_levels && rng() % 2 == 0)
      v = static_cast<std::int8_t>(rng() % 101);
    r.cells.push_back(v);
  }
  return r;
}

void expectRoundTrip(const RasterMap& raster, const RosMapSaveOptions& options) {
  test::TempDir dir;
  ASSERT_EQ(saveRosMap(raster, dir / "map.yaml", options), std::nullopt);
  EXPECT_TRUE(fs::exists(dir / "map.pgm"));
  const RosMapLoadResult r = loadRosMap(dir / "map.yaml");
  ASSERT_TRUE(r.raster) << allDiagnostics(r);
  EXPECT_TRUE(r.diagnostics.empty()) << allDiagnostics(r);
  EXPECT_EQ(r.metadata.mode, options.mode);
  EXPECT_EQ(r.raster->width, raster.width);
  EXPECT_EQ(r.raster->height, raster.height);
  EXPECT_EQ(r.raster->resolution_m, raster.resolution_m);
  EXPECT_EQ(r.raster->origin, raster.origin);
  EXPECT_EQ(r.raster->cells, raster.cells);
}

TEST(RosMap, TrinaryRoundTripKeepsFreeOccupiedAndUnknown) {
  std::mt19937 rng(1);
  expectRoundTrip(randomRaster(rng, true, false), {});
  RosMapSaveOptions negate;
  negate.negate = true;
  expectRoundTrip(randomRaster(rng, true, false), negate);
  // Thresholds for which the customary 205 grey would read back as free.
  RosMapSaveOptions wide;
  wide.free_thresh = 0.25;
  expectRoundTrip(randomRaster(rng, true, false), wide);
}

TEST(RosMap, ScaleRoundTripKeepsEveryLevel) {
  std::mt19937 rng(2);
  RosMapSaveOptions scale;
  scale.mode = RosMapMode::kScale;
  expectRoundTrip(randomRaster(rng, false, true), scale);
  scale.negate = true;
  expectRoundTrip(randomRaster(rng, false, true), scale);
}

TEST(RosMap, RawRoundTripKeepsEverything) {
  std::mt19937 rng(3);
  RosMapSaveOptions raw;
  raw.mode = RosMapMode::kRaw;
  expectRoundTrip(randomRaster(rng, true, true), raw);
}

TEST(RosMap, SavedYamlUsesTheMapServerKeys) {
  test::TempDir dir;
  std::mt19937 rng(4);
  ASSERT_EQ(saveRosMap(randomRaster(rng, true, false), dir / "lab.yaml"), std::nullopt);
  const ReadFileResult yaml = readFile(dir / "lab.yaml");
  EXPECT_EQ(yaml.bytes,
            "image: lab.pgm\nmode: trinary\nresolution: 0.05\norigin: [-1.25, 3.5, 0]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
}

TEST(RosMap, SaveRejectsBadInput) {
  test::TempDir dir;
  RasterMap empty;
  EXPECT_TRUE(saveRosMap(empty, dir / "a.yaml"));
  std::mt19937 rng(5);
  RasterMap r = randomRaster(rng, true, false);
  RosMapSaveOptions bad;
  bad.free_thresh = 0.7;
  EXPECT_TRUE(saveRosMap(r, dir / "a.yaml", bad));
  EXPECT_TRUE(saveRosMap(r, dir / "a.pgm"));
  r.resolution_m = 0.0;
  EXPECT_TRUE(saveRosMap(r, dir / "a.yaml"));
  EXPECT_FALSE(fs::exists(dir / "a.yaml"));
}

struct YamlCase {
  const char* name;
  const char* yaml;
  const char* field;
  const char* message_part;
  int line;
};

TEST(RosMap, BadYamlIsReportedWithFileLineAndKey) {
  test::TempDir dir;
  ASSERT_EQ(writePgmFile(GrayImage{2, 2, {0, 254, 205, 0}}, dir / "ok.pgm"), std::nullopt);
  ASSERT_EQ(writeFileAtomically(dir / "short.pgm", "P5 4 4 255\nabc"), std::nullopt);
  const YamlCase cases[] = {
      {"syntax", "image: ok.pgm\nresolution: [0.05\n", "", "YAML syntax error", 3},
      {"not a mapping", "- 1\n- 2\n", "", "expected a mapping", 1},
      {"missing resolution", "image: ok.pgm\norigin: [0, 0, 0]\n", "resolution",
       "missing required key", 1},
      {"resolution text", "image: ok.pgm\nresolution: fine\norigin: [0, 0, 0]\n", "resolution",
       "expected a number", 2},
      {"negative resolution", "image: ok.pgm\nresolution: -1\norigin: [0, 0, 0]\n", "resolution",
       "positive", 2},
      {"short origin", "image: ok.pgm\nresolution: 0.1\norigin: [0, 0]\n", "origin",
       "three numbers", 3},
      {"bad origin entry", "image: ok.pgm\nresolution: 0.1\norigin: [0, .nan, 0]\n", "origin/1",
       "finite", 3},
      {"bad mode", "image: ok.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nmode: fancy\n", "mode",
       "trinary, scale or raw", 4},
      {"bad negate", "image: ok.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 2\n", "negate",
       "0 or 1", 4},
      {"crossed thresholds",
       "image: ok.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nfree_thresh: 0.7\n"
       "occupied_thresh: 0.6\n",
       "free_thresh", "smaller than occupied_thresh", 4},
      {"missing image file", "image: none.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n", "image",
       "cannot load the image", 1},
      {"short image", "image: short.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n", "image",
       "cannot load the image", 1},
  };
  for (const YamlCase& c : cases) {
    SCOPED_TRACE(c.name);
    const RosMapLoadResult r = parseRosMap(c.yaml, "m.yaml", dir.path());
    EXPECT_FALSE(r.raster);
    const Diagnostic d = firstError(r);
    EXPECT_EQ(d.file, "m.yaml");
    EXPECT_EQ(d.field, c.field);
    EXPECT_NE(d.message.find(c.message_part), std::string::npos) << d.toString();
    EXPECT_EQ(d.line, c.line) << d.toString();
  }
  // The image's own problem follows, naming the image file.
  const RosMapLoadResult r =
      parseRosMap("image: short.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n", "m.yaml", dir.path());
  ASSERT_EQ(r.diagnostics.size(), 5U) << allDiagnostics(r);  // 3 warnings, yaml error, pgm error
  EXPECT_NE(r.diagnostics.back().file.find("short.pgm"), std::string::npos);
  EXPECT_NE(r.diagnostics.back().message.find("truncated"), std::string::npos);
}

TEST(RosMap, MissingOptionalKeysWarnAndUseDefaults) {
  test::TempDir dir;
  ASSERT_EQ(writePgmFile(GrayImage{1, 1, {0}}, dir / "one.pgm"), std::nullopt);
  const RosMapLoadResult r =
      parseRosMap("image: one.pgm\nresolution: 0.1\norigin: [1, 2, 0.5]\n", "m.yaml", dir.path());
  ASSERT_TRUE(r.raster) << allDiagnostics(r);
  EXPECT_EQ(r.raster->cells, std::vector<std::int8_t>{100});
  EXPECT_EQ(r.raster->origin, (Pose2{1, 2, 0.5}));
  int warnings = 0;
  for (const auto& d : r.diagnostics)
    warnings += d.severity == Severity::kWarning ? 1 : 0;
  EXPECT_EQ(warnings, 4);  // negate, occupied_thresh, free_thresh, non-zero yaw
  EXPECT_FALSE(loadRosMap(dir / "missing.yaml").raster);
}

// The real maps in ../shared/maps/ros (not part of the project: skipped when absent).
fs::path sharedRosMaps() {
  for (const fs::path& p : {fs::path("../shared/maps/ros"),
                            fs::path(IRGS_SOURCE_DIR) / ".." / "shared" / "maps" / "ros"}) {
    if (fs::is_directory(p))
      return p;
  }
  return {};
}

TEST(RosMap, LoadsEverySharedRosMapAndRoundTripsIt) {
  const fs::path folder = sharedRosMaps();
  if (folder.empty())
    GTEST_SKIP() << "../shared/maps/ros is not present (it is not part of the project)";
  int maps = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".yaml")
      continue;
    ++maps;
    SCOPED_TRACE(entry.path().string());
    const RosMapLoadResult r = loadRosMap(entry.path());
    ASSERT_TRUE(r.raster) << allDiagnostics(r);
    EXPECT_FALSE(hasErrors(r.diagnostics));
    const RasterMap& raster = *r.raster;
    const auto count = [&](std::int8_t v) {
      return std::count(raster.cells.begin(), raster.cells.end(), v);
    };
    EXPECT_GT(count(RasterMap::kFree), 0);
    EXPECT_GT(count(RasterMap::kOccupied), 0);
    EXPECT_EQ(count(RasterMap::kFree) + count(RasterMap::kOccupied) + count(RasterMap::kUnknown),
              static_cast<long>(raster.cells.size()));
    const std::string stem = entry.path().stem().string();
    if (stem == "warehouse") {
      EXPECT_EQ(raster.width, 1006);
      EXPECT_EQ(raster.height, 1674);
      EXPECT_DOUBLE_EQ(raster.resolution_m, 0.03);
      EXPECT_EQ(raster.origin, (Pose2{-15.1, -25.0, 0.0}));
    } else if (stem == "depot") {
      EXPECT_EQ(raster.width, 604);
      EXPECT_EQ(raster.height, 307);
      EXPECT_DOUBLE_EQ(raster.resolution_m, 0.05);
    } else if (stem == "tb3_sandbox") {
      EXPECT_EQ(raster.width, 384);
      EXPECT_EQ(raster.height, 384);
      EXPECT_EQ(raster.origin, (Pose2{-10.0, -10.0, 0.0}));
    }

    test::TempDir dir;
    ASSERT_EQ(saveRosMap(raster, dir / (stem + ".yaml")), std::nullopt);
    const RosMapLoadResult again = loadRosMap(dir / (stem + ".yaml"));
    ASSERT_TRUE(again.raster) << allDiagnostics(again);
    EXPECT_EQ(again.raster->cells, raster.cells);
    EXPECT_EQ(again.raster->origin, raster.origin);

    // A start pose with 0.25 m of free space around it, checked cell by cell.
    const auto start = std::chrono::steady_clock::now();
    StartPoseSearch search;
    const WorldMap world = worldFromRaster(raster, entry.path().string(), 0.25, &search);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 5.0) << "start pose search is too slow";
    ASSERT_TRUE(search.found);
    const auto cell = raster.worldToCell(world.start.position());
    ASSERT_TRUE(cell);
    const int reach = static_cast<int>(std::ceil(0.25 / raster.resolution_m)) + 1;
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const int x = cell->first + dx, y = cell->second + dy;
        if ((std::hypot(dx, dy) - 0.5) * raster.resolution_m >= 0.25)
          continue;
        ASSERT_TRUE(raster.inside(x, y));
        EXPECT_TRUE(isFreeCell(raster.at(x, y))) << dx << ", " << dy;
      }
    }
  }
  EXPECT_GE(maps, 3);
}

}  // namespace
}  // namespace irgs
