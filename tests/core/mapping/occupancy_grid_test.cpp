#include "core/mapping/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace irgs {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A log-odds as the grid's cells hold it: a whole number of steps of 1/4096, rounded away from
// zero (occupancy_grid.hpp).
float inCellSteps(double log_odds) {
  const double steps = std::ceil(std::abs(log_odds) * 4096.0);
  return static_cast<float>((log_odds < 0.0 ? -steps : steps) / 4096.0);
}

// Renders cells [col0, col1] x [row1 down to row0] as text: ' ' unobserved, '.' free
// (log-odds < 0), '#' occupied (> 0), '?' observed but exactly 0.
std::vector<std::string> render(const OccupancyGrid& grid, int col0, int col1, int row0, int row1) {
  std::vector<std::string> lines;
  for (int row = row1; row >= row0; --row) {
    std::string line;
    for (int col = col0; col <= col1; ++col) {
      const Cell c{col, row};
      if (!grid.observed(c))
        line += ' ';
      else
        line += grid.logOdds(c) < 0.0f ? '.' : grid.logOdds(c) > 0.0f ? '#' : '?';
    }
    lines.push_back(line);
  }
  return lines;
}

// The first cell where two grids differ, for a readable failure.
std::string firstDifference(const OccupancyGrid& a, const OccupancyGrid& b) {
  OccupancyGrid::CellRect r = a.observedCellRect();
  r.extend(b.observedCellRect());
  for (int row = r.row0; row <= r.row1; ++row) {
    for (int col = r.col0; col <= r.col1; ++col) {
      const Cell c{col, row};
      if (a.observed(c) != b.observed(c) || a.logOdds(c) != b.logOdds(c)) {
        std::ostringstream out;
        out << "cell (" << col << ", " << row << "): observed " << a.observed(c) << " vs "
            << b.observed(c) << ", log-odds " << a.logOdds(c) << " vs " << b.logOdds(c);
        return out.str();
      }
    }
  }
  return "no cell differs (counters differ)";
}

TEST(OccupancyGrid, NewGridHasNothingObserved) {
  OccupancyGrid grid;
  EXPECT_DOUBLE_EQ(grid.resolution_m(), 0.01);
  EXPECT_FALSE(grid.observed({3, -4}));
  EXPECT_EQ(grid.logOdds({3, -4}), 0.0f);
  EXPECT_DOUBLE_EQ(grid.probability({3, -4}), 0.5);
  EXPECT_TRUE(grid.observedBounds().empty());
  EXPECT_TRUE(grid.observedCellRect().empty());
  EXPECT_EQ(grid.exploredArea_m2(), 0.0);
  EXPECT_TRUE(grid.takeDirtyRect().empty());
  EXPECT_TRUE(grid.toRaster().empty());
  EXPECT_EQ(grid.tileCount(), 0u);
}

TEST(OccupancyGrid, RejectsResolutionThatIsNotPositiveAndFinite) {
  EXPECT_THROW(OccupancyGrid(0.0), std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(-0.01), std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(std::nan("")), std::invalid_argument);
  EXPECT_THROW(OccupancyGrid{kInf}, std::invalid_argument);
}

TEST(OccupancyGrid, CellAtFloorsTowardsMinusInfinityAndCentresRoundTrip) {
  const OccupancyGrid grid(0.1);
  EXPECT_EQ(grid.cellAt({0.05, 0.05}), (Cell{0, 0}));
  EXPECT_EQ(grid.cellAt({-0.001, 0.0}), (Cell{-1, 0}));
  EXPECT_EQ(grid.cellAt({-0.25, -0.31}), (Cell{-3, -4}));
  for (const Cell c : {Cell{0, 0}, Cell{-7, 12}, Cell{1000, -1000}})
    EXPECT_EQ(grid.cellAt(grid.cellCentre(c)), c);
  EXPECT_NEAR(grid.cellCentre({-3, 2}).x(), -0.25, 1e-12);
  EXPECT_NEAR(grid.cellCentre({-3, 2}).y(), 0.25, 1e-12);
  EXPECT_THROW(grid.cellAt({std::nan(""), 0.0}), std::out_of_range);
  EXPECT_THROW(grid.cellAt({1e300, 0.0}), std::out_of_range);
  EXPECT_FALSE(grid.isAddressable({1e300, 0.0}));
  EXPECT_TRUE(grid.isAddressable({1e6, -1e6}, 5.0));
}

TEST(OccupancyGrid, SimpleConeMarksLiteralFreeAndOccupiedCells) {
  // 10 cm cells, apex at the origin looking along +x, 60 degree beam, echo at 0.7 m, arc 0.1 m:
  // free where |d| < 0.65 m, occupied where 0.65 <= |d| <= 0.75 m, both within +-30 degrees.
  OccupancyGrid grid(0.1);
  SonarInverseModel model;
  model.arc_thickness_m = 0.1;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(60.0), 0.7, true, model);
  const std::vector<std::string> expected = {
      "          ",  // row 5
      "          ",  // row 4
      "       #  ",  // row 3
      "     ..#  ",  // row 2
      "    ...#  ",  // row 1
      "  .....#  ",  // row 0
      "  .....#  ",  // row -1
      "    ...#  ",  // row -2
      "     ..#  ",  // row -3
      "       #  ",  // row -4
      "          ",  // row -5
  };                 // columns -1 .. 8
  EXPECT_EQ(render(grid, -1, 8, -5, 5), expected);
  EXPECT_EQ(grid.observedCellCount(), 28u);
  EXPECT_EQ(grid.cellUpdates(), 28u);
}

TEST(OccupancyGrid, ConeLooksAlongItsHeading) {
  // The same cone turned to +y: free cells lie above the apex, none below.
  OccupancyGrid grid(0.01);
  grid.integrateSonar({0.0, 0.0}, kPi / 2.0, degToRad(30.0), 1.0, true, {});
  EXPECT_LT(grid.logOdds(grid.cellAt({0.0, 0.5})), 0.0f);
  EXPECT_GT(grid.logOdds(grid.cellAt({0.02, 1.0})), 0.0f);
  EXPECT_FALSE(grid.observed(grid.cellAt({0.0, -0.5})));
  EXPECT_FALSE(grid.observed(grid.cellAt({0.5, 0.0})));
  EXPECT_FALSE(grid.observed(grid.cellAt({0.0, 1.3})));
}

TEST(OccupancyGrid, FreeCellsGetTheFreeIncrementAndArcCellsTheOccupiedOne) {
  OccupancyGrid grid(0.01);
  SonarInverseModel model;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 2.0, true, model);
  EXPECT_EQ(grid.logOdds(grid.cellAt({1.0, 0.0})), -1639.0f / 4096.0f);  // -0.4 in cell steps
  EXPECT_EQ(grid.logOdds(grid.cellAt({2.0, 0.0})), 3482.0f / 4096.0f);   // 0.85
  EXPECT_LT(grid.probability(grid.cellAt({1.0, 0.0})), 0.5);
  EXPECT_GT(grid.probability(grid.cellAt({2.0, 0.0})), 0.5);
  EXPECT_FALSE(grid.observed(grid.cellAt({2.1, 0.0})));
}

TEST(OccupancyGrid, RepeatedReadingsClampLogOdds) {
  OccupancyGrid grid(0.02);
  SonarInverseModel model;
  model.clamp_min = -1.0;
  model.clamp_max = 2.0;
  for (int i = 0; i < 50; ++i)
    grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, model);
  EXPECT_FLOAT_EQ(grid.logOdds(grid.cellAt({0.5, 0.0})), -1.0f);
  EXPECT_FLOAT_EQ(grid.logOdds(grid.cellAt({1.0, 0.0})), 2.0f);
  // Observed cells are counted once, however often they are updated.
  OccupancyGrid once(0.02);
  once.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, model);
  EXPECT_EQ(grid.observedCellCount(), once.observedCellCount());
  EXPECT_EQ(grid.cellUpdates(), 50 * once.cellUpdates());
}

TEST(OccupancyGrid, NoEchoClearsFreeSpaceUpToTheNoEchoRangeOnly) {
  OccupancyGrid grid(0.01);
  SonarInverseModel model;
  model.no_echo_free_range_m = 1.5;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 4.0, false, model);
  EXPECT_LT(grid.logOdds(grid.cellAt({1.45, 0.0})), 0.0f);
  EXPECT_FALSE(grid.observed(grid.cellAt({1.55, 0.0})));
  // Capped at the range when the range is shorter.
  OccupancyGrid short_range(0.01);
  short_range.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 0.5, false, model);
  EXPECT_LT(short_range.logOdds(short_range.cellAt({0.45, 0.0})), 0.0f);
  EXPECT_FALSE(short_range.observed(short_range.cellAt({0.55, 0.0})));
  // Nothing is ever marked occupied without an echo.
  for (const auto& r : {grid, short_range}) {
    const OccupancyGrid::CellRect box = r.observedCellRect();
    for (int row = box.row0; row <= box.row1; ++row)
      for (int col = box.col0; col <= box.col1; ++col)
        ASSERT_LE(r.logOdds({col, row}), 0.0f);
  }
}

TEST(OccupancyGrid, NoEchoFreeRangeZeroDisablesClearing) {
  OccupancyGrid grid(0.01);
  SonarInverseModel model;
  model.no_echo_free_range_m = 0.0;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 4.0, false, model);
  EXPECT_EQ(grid.observedCellCount(), 0u);
  EXPECT_TRUE(grid.takeDirtyRect().empty());
}

TEST(OccupancyGrid, GrowsInNegativeDirections) {
  OccupancyGrid grid(0.01);
  grid.integrateSonar({-50.0, -30.0}, -3.0 * kPi / 4.0, degToRad(25.0), 1.0, true, {});
  const Vec2 far =
      Vec2(-50.0, -30.0) + 0.5 * Vec2(std::cos(-3.0 * kPi / 4.0), std::sin(-3.0 * kPi / 4.0));
  EXPECT_LT(grid.logOdds(grid.cellAt(far)), 0.0f);
  const Box2 bounds = grid.observedBounds();
  EXPECT_LT(bounds.max.x(), -49.9);
  EXPECT_LT(bounds.max.y(), -29.9);
  EXPECT_GT(bounds.min.x(), -50.9);  // reach 1.015 m at 147.5 degrees off +x
  EXPECT_GT(bounds.min.y(), -30.9);
  EXPECT_LT(bounds.min.x(), -50.8);
  EXPECT_LT(bounds.min.y(), -30.8);
  // And keeps what it had when it grows elsewhere.
  grid.integrateSonar({20.0, 40.0}, 0.3, degToRad(25.0), 1.0, true, {});
  EXPECT_LT(grid.logOdds(grid.cellAt(far)), 0.0f);
  EXPECT_GT(grid.observedBounds().max.x(), 20.9);
}

TEST(OccupancyGrid, DirtyRectCoversTouchedCellsAndResetsWhenTaken) {
  OccupancyGrid grid(0.1);
  SonarInverseModel model;
  model.arc_thickness_m = 0.1;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(60.0), 0.7, true, model);
  const OccupancyGrid::CellRect dirty = grid.takeDirtyRect();
  EXPECT_EQ(dirty, (OccupancyGrid::CellRect{1, -4, 6, 3}));  // the literal cone above
  EXPECT_TRUE(grid.takeDirtyRect().empty());
  grid.integrateSonar({-1.0, 0.0}, kPi, degToRad(60.0), 0.7, true, model);
  const OccupancyGrid::CellRect second = grid.takeDirtyRect();
  EXPECT_EQ(second, (OccupancyGrid::CellRect{-17, -4, -12, 3}));  // mirrored about x = -1
  // The observed rect keeps everything.
  EXPECT_EQ(grid.observedCellRect(), (OccupancyGrid::CellRect{-17, -4, 6, 3}));
}

TEST(OccupancyGrid, ToRasterHasOriginAtObservedBoundsAndRosValues) {
  OccupancyGrid grid(0.1);
  SonarInverseModel model;
  model.arc_thickness_m = 0.1;
  model.free_log_odds = -2.0;
  model.occupied_log_odds = 3.0;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(60.0), 0.7, true, model);
  const RasterMap raster = grid.toRaster();
  ASSERT_EQ(raster.width, 6);
  ASSERT_EQ(raster.height, 8);
  EXPECT_DOUBLE_EQ(raster.resolution_m, 0.1);
  EXPECT_NEAR(raster.origin.x, 0.1, 1e-12);
  EXPECT_NEAR(raster.origin.y, -0.4, 1e-12);
  EXPECT_EQ(raster.origin.theta, 0.0);
  // p = 1 / (1 + exp(-l)): l = -2 -> 11.9 %, l = 3 -> 95.3 %.
  const auto at = [&](int col, int row) { return raster.at(col - 1, row + 4); };
  EXPECT_EQ(at(1, 0), 12);
  EXPECT_EQ(at(6, 0), 95);
  EXPECT_EQ(at(1, 3), RasterMap::kUnknown);
  EXPECT_EQ(at(6, 3), 95);
  const Box2 b = grid.observedBounds();
  EXPECT_NEAR(b.min.x(), 0.1, 1e-12);
  EXPECT_NEAR(b.max.y(), 0.4, 1e-12);
}

TEST(OccupancyGrid, ExploredAreaCountsEachObservedCellOnce) {
  OccupancyGrid grid(0.1);
  SonarInverseModel model;
  model.arc_thickness_m = 0.1;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(60.0), 0.7, true, model);
  EXPECT_NEAR(grid.exploredArea_m2(), 28 * 0.01, 1e-12);
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(60.0), 0.7, true, model);
  EXPECT_NEAR(grid.exploredArea_m2(), 28 * 0.01, 1e-12);
  // A 25 degree, 2 m no-echo cone covers about (25/360) * pi * 1.5^2 m² at 1 cm.
  OccupancyGrid fine(0.01);
  fine.integrateSonar({0.3, 0.2}, 1.0, degToRad(25.0), 2.0, false, {});
  EXPECT_NEAR(fine.exploredArea_m2(), 25.0 / 360.0 * kPi * 1.5 * 1.5, 0.005);
}

TEST(OccupancyGrid, CopiesAreDeepAndIndependent) {
  OccupancyGrid a(0.05);
  a.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, {});
  OccupancyGrid b = a;
  EXPECT_TRUE(a == b);
  b.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, {});
  EXPECT_FALSE(a == b);
  EXPECT_EQ(a.logOdds(a.cellAt({0.5, 0.0})), inCellSteps(-0.4));
  EXPECT_EQ(b.logOdds(b.cellAt({0.5, 0.0})), 2.0f * inCellSteps(-0.4));
  OccupancyGrid c(0.05);
  c = b;
  a.integrateSonar({5.0, 5.0}, 0.0, degToRad(25.0), 1.0, true, {});
  EXPECT_TRUE(c == b);
  EXPECT_FALSE(c.observed(c.cellAt({5.5, 5.0})));
  // Moving leaves an empty grid behind.
  OccupancyGrid d = std::move(c);
  EXPECT_TRUE(d == b);
  EXPECT_EQ(c.observedCellCount(), 0u);  // NOLINT(bugprone-use-after-move): documented state
  EXPECT_FALSE(c.observed(c.cellAt({0.5, 0.0})));
  EXPECT_TRUE(c.observedCellRect().empty());
}

TEST(OccupancyGrid, CopyLogOddsReturnsValuesRowMajorAndNanForUnknown) {
  OccupancyGrid grid(0.1);
  SonarInverseModel model;
  model.arc_thickness_m = 0.1;
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(60.0), 0.7, true, model);
  // A rect straddling tile boundaries (tiles are 64 cells) and unobserved space.
  const OccupancyGrid::CellRect rect{-70, -5, 8, 70};
  std::vector<float> values;
  grid.copyLogOdds(rect, values);
  ASSERT_EQ(values.size(), static_cast<std::size_t>(79 * 76));
  for (int row = rect.row0; row <= rect.row1; ++row) {
    for (int col = rect.col0; col <= rect.col1; ++col) {
      const float v = values[static_cast<std::size_t>((row - rect.row0) * 79 + (col - rect.col0))];
      if (grid.observed({col, row})) {
        ASSERT_EQ(v, grid.logOdds({col, row})) << col << ", " << row;
      } else {
        ASSERT_TRUE(std::isnan(v)) << col << ", " << row;
      }
    }
  }
  grid.copyLogOdds({}, values);
  EXPECT_TRUE(values.empty());
}

TEST(OccupancyGrid, RejectsInvalidConeArguments) {
  OccupancyGrid grid(0.01);
  const SonarInverseModel ok;
  const double beam = degToRad(25.0);
  EXPECT_THROW(grid.integrateSonar({std::nan(""), 0.0}, 0.0, beam, 1.0, true, ok),
               std::invalid_argument);
  EXPECT_THROW(grid.integrateSonar({0.0, 0.0}, kInf, beam, 1.0, true, ok), std::invalid_argument);
  EXPECT_THROW(grid.integrateSonar({0.0, 0.0}, 0.0, 0.0, 1.0, true, ok), std::invalid_argument);
  EXPECT_THROW(grid.integrateSonar({0.0, 0.0}, 0.0, kPi, 1.0, true, ok), std::invalid_argument);
  EXPECT_THROW(grid.integrateSonar({0.0, 0.0}, 0.0, beam, -1.0, true, ok), std::invalid_argument);
  EXPECT_THROW(grid.integrateSonar({0.0, 0.0}, 0.0, beam, std::nan(""), true, ok),
               std::invalid_argument);
  EXPECT_THROW(grid.integrateSonar({0.0, 0.0}, 0.0, beam, 1000.0, true, ok),
               std::invalid_argument);  // radius beyond kMaxConeRadiusCells
  EXPECT_THROW(grid.integrateSonar({1.1e7, 0.0}, 0.0, beam, 1.0, true, ok), std::invalid_argument);
  SonarInverseModel bad;
  bad.clamp_min = 1.0;
  bad.clamp_max = -1.0;
  EXPECT_THROW(grid.integrateSonar({0.0, 0.0}, 0.0, beam, 1.0, true, bad), std::invalid_argument);
  EXPECT_TRUE(sonarInverseModelError(bad).has_value());
  EXPECT_FALSE(sonarInverseModelError(ok).has_value());
  EXPECT_EQ(grid.observedCellCount(), 0u);  // nothing half-applied
}

TEST(OccupancyGrid, ModelValuesMustFitTheSixteenBitCells) {
  const auto error = [](double SonarInverseModel::*field, double value) {
    SonarInverseModel model;
    model.clamp_min = -OccupancyGrid::kMaxAbsLogOdds;
    model.clamp_max = OccupancyGrid::kMaxAbsLogOdds;
    model.*field = value;
    return sonarInverseModelError(model);
  };
  for (const auto field : {&SonarInverseModel::free_log_odds, &SonarInverseModel::occupied_log_odds,
                           &SonarInverseModel::clamp_min, &SonarInverseModel::clamp_max}) {
    const double sign = field == &SonarInverseModel::clamp_min ? -1.0 : 1.0;
    EXPECT_FALSE(error(field, sign * OccupancyGrid::kMaxAbsLogOdds));
    const auto beyond = error(field, sign * (OccupancyGrid::kMaxAbsLogOdds + 1e-9));
    ASSERT_TRUE(beyond);
    EXPECT_NE(beyond->find("16-bit"), std::string::npos) << *beyond;
    EXPECT_TRUE(error(field, std::nan("")));
  }
  SonarInverseModel too_high;
  too_high.clamp_max = 10.0;
  OccupancyGrid grid(0.01);
  EXPECT_THROW(grid.integrateSonar({0.0, 0.0}, 0.0, 0.5, 1.0, true, too_high),
               std::invalid_argument);
}

TEST(OccupancyGrid, IncrementsAndClampsRoundAwayFromZeroToCellSteps) {
  OccupancyGrid grid(0.01);
  SonarInverseModel model;
  model.free_log_odds = -0.3;      // -1228.8 steps: -1229
  model.occupied_log_odds = 1e-6;  // below one step: still one
  model.clamp_min = -0.5;          // -2048 steps, exact
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, model);
  EXPECT_EQ(grid.logOdds(grid.cellAt({0.5, 0.0})), -1229.0f / 4096.0f);
  EXPECT_EQ(grid.logOdds(grid.cellAt({1.0, 0.0})), 1.0f / 4096.0f);
  EXPECT_LT(grid.logOdds(grid.cellAt({0.5, 0.0})), -0.3);  // never weaker than the model's
  grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, model);
  EXPECT_EQ(grid.logOdds(grid.cellAt({0.5, 0.0})), -0.5f);  // clamped
}

// A random cone of the kind the robot produces, and the awkward ones: headings near +-pi, beams
// 5..60 degrees, ranges from below one cell to 4 m, with and without echo.
struct RandomCone {
  Vec2 origin;
  double heading_rad, beam_rad, range_m;
  bool echo;
};

RandomCone randomCone(std::mt19937_64& rng, double max_range_m) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  RandomCone c;
  c.origin = Vec2(-5.0 + 10.0 * unit(rng), -5.0 + 10.0 * unit(rng));
  const double kind = unit(rng);
  if (kind < 0.2)
    c.heading_rad = kPi - 1e-9 * unit(rng);  // just below +pi
  else if (kind < 0.4)
    c.heading_rad = -kPi + 1e-9 * unit(rng);  // just above -pi
  else
    c.heading_rad = -4.0 * kPi + 8.0 * kPi * unit(rng);  // unwrapped too
  c.beam_rad = degToRad(5.0 + 55.0 * unit(rng));
  const double size = unit(rng);
  c.range_m = size < 0.15 ? 0.03 * unit(rng) : max_range_m * unit(rng);
  c.echo = unit(rng) < 0.7;
  return c;
}

// Every instruction set the machine supports (the grid's results must not depend on it).
std::vector<GridSimd> supportedSimd() {
  std::vector<GridSimd> out;
  for (const GridSimd simd : {GridSimd::kPortable, GridSimd::kAvx2, GridSimd::kAvx512})
    if (gridSimdSupported(simd))
      out.push_back(simd);
  return out;
}

TEST(OccupancyGrid, FastConeEqualsNaiveReferenceOnRandomCones) {
  std::mt19937_64 rng(20240611);
  struct Setup {
    double resolution_m, max_range_m;
    int cones;
  };
  for (const GridSimd simd : supportedSimd()) {
    SCOPED_TRACE("simd " + std::to_string(static_cast<int>(simd)));
    for (const Setup setup :
         {Setup{0.01, 1.0, 1000}, Setup{0.05, 4.0, 1500}, Setup{0.013, 0.3, 1500}}) {
      SonarInverseModel model;
      for (int i = 0; i < setup.cones; ++i) {
        const RandomCone c = randomCone(rng, setup.max_range_m);
        model.arc_thickness_m =
            i % 3 == 0 ? 0.0 : 0.1 * std::uniform_real_distribution<>(0, 1)(rng);
        OccupancyGrid fast(setup.resolution_m), naive(setup.resolution_m);
        fast.setSimd(simd);
        fast.integrateSonar(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
        naive.integrateSonarNaive(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
        ASSERT_TRUE(fast == naive)
            << "cone " << i << " at (" << c.origin.x() << ", " << c.origin.y() << ") heading "
            << c.heading_rad << " beam " << c.beam_rad << " range " << c.range_m << " echo "
            << c.echo << ": " << firstDifference(fast, naive);
        ASSERT_EQ(fast.cellUpdates(), naive.cellUpdates());
        ASSERT_EQ(fast.observedCellRect(), naive.observedCellRect());
      }
    }
  }
}

TEST(OccupancyGrid, FastAndNaiveAccumulateToTheSameGrid) {
  for (const GridSimd simd : supportedSimd()) {
    SCOPED_TRACE("simd " + std::to_string(static_cast<int>(simd)));
    std::mt19937_64 rng(7);
    OccupancyGrid fast(0.02), naive(0.02);
    fast.setSimd(simd);
    SonarInverseModel model;
    model.clamp_min = -1.0;  // reached after 3 free updates: exercises clamping on both paths
    for (int i = 0; i < 300; ++i) {
      RandomCone c = randomCone(rng, 2.0);
      c.origin *= 0.2;  // overlapping cones
      fast.integrateSonar(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
      naive.integrateSonarNaive(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
    }
    EXPECT_TRUE(fast == naive) << firstDifference(fast, naive);
    EXPECT_EQ(fast.exploredArea_m2(), naive.exploredArea_m2());
    EXPECT_EQ(fast.takeDirtyRect(), naive.takeDirtyRect());
  }
}

TEST(OccupancyGrid, SaturatingSumsEqualTheExactClampedSum) {
  // The SIMD paths add in 16 bits with saturation; with increments near the cells' limit and
  // models whose clamps differ (cells beyond the current model's clamps), every path must still
  // give the exact sum clamped to the current model's [clamp_min, clamp_max].
  SonarInverseModel wide;
  wide.free_log_odds = -OccupancyGrid::kMaxAbsLogOdds;
  wide.occupied_log_odds = OccupancyGrid::kMaxAbsLogOdds;
  wide.clamp_min = -OccupancyGrid::kMaxAbsLogOdds;
  wide.clamp_max = OccupancyGrid::kMaxAbsLogOdds;
  SonarInverseModel narrow = wide;
  narrow.clamp_min = -0.5;
  narrow.clamp_max = 0.25;
  SonarInverseModel inverted = wide;  // free cells pushed up, arcs down
  inverted.free_log_odds = 7.5;
  inverted.occupied_log_odds = -7.5;
  const SonarInverseModel models[] = {wide, narrow, inverted};
  for (const GridSimd simd : supportedSimd()) {
    SCOPED_TRACE("simd " + std::to_string(static_cast<int>(simd)));
    std::mt19937_64 rng(31);
    OccupancyGrid fast(0.02), naive(0.02);
    fast.setSimd(simd);
    for (int i = 0; i < 300; ++i) {
      RandomCone c = randomCone(rng, 2.0);
      c.origin *= 0.2;
      const SonarInverseModel& model = models[rng() % 3];
      fast.integrateSonar(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
      naive.integrateSonarNaive(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
    }
    EXPECT_TRUE(fast == naive) << firstDifference(fast, naive);
    // One cell by hand: two wide free updates stop at the floor, a narrow one lifts it to -0.5
    // (not -0.5 minus the increment), an inverted one adds 7.5 to that.
    OccupancyGrid grid(0.01);
    grid.setSimd(simd);
    const Cell cell = grid.cellAt({0.5, 0.0});
    for (const SonarInverseModel* m : {&wide, &wide})
      grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, *m);
    EXPECT_EQ(grid.logOdds(cell), -32767.0f / 4096.0f);
    grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, narrow);
    EXPECT_EQ(grid.logOdds(cell), -0.5f);
    grid.integrateSonar({0.0, 0.0}, 0.0, degToRad(25.0), 1.0, true, inverted);
    EXPECT_EQ(grid.logOdds(cell), 7.0f);
  }
}

TEST(OccupancyGrid, TilesThatShareACacheSlotStayApart) {
  // integrateSonar finds tiles through a direct-mapped cache indexed by the low 5 bits of the
  // tile coordinates: tiles 32 apart (20.48 m at 1 cm) share a slot. Cones alternating between
  // such places, then continuing in a moved and a copied grid, must write where the naive
  // reference does.
  for (const GridSimd simd : supportedSimd()) {
    SCOPED_TRACE("simd " + std::to_string(static_cast<int>(simd)));
    const double res = 0.01;
    const double period = 32.0 * OccupancyGrid::kTileSize * res;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    SonarInverseModel model;
    OccupancyGrid fast(res), naive(res);
    fast.setSimd(simd);
    const auto both = [&](OccupancyGrid& f, OccupancyGrid& n) {
      const Vec2 origin(1.0 + 0.5 * unit(rng) + period * std::floor(3.0 * unit(rng) - 1.0),
                        2.0 + 0.5 * unit(rng) + period * std::floor(3.0 * unit(rng) - 1.0));
      const double heading = 2.0 * kPi * unit(rng), range = 1.5 * unit(rng);
      f.integrateSonar(origin, heading, degToRad(30.0), range, true, model);
      n.integrateSonarNaive(origin, heading, degToRad(30.0), range, true, model);
    };
    for (int i = 0; i < 60; ++i)
      both(fast, naive);
    ASSERT_TRUE(fast == naive) << firstDifference(fast, naive);
    OccupancyGrid moved = std::move(fast);
    OccupancyGrid copied = moved;
    OccupancyGrid naive_copy = naive;
    for (int i = 0; i < 30; ++i) {
      both(moved, naive);
      both(copied, naive_copy);
    }
    EXPECT_TRUE(moved == naive) << firstDifference(moved, naive);
    EXPECT_TRUE(copied == naive_copy) << firstDifference(copied, naive_copy);
    // Assignments replace the tiles the cache pointed into.
    OccupancyGrid reassigned(res), scratch(res);
    reassigned.setSimd(simd);
    both(reassigned, scratch);
    reassigned = std::move(copied);
    for (int i = 0; i < 30; ++i)
      both(reassigned, naive_copy);
    EXPECT_TRUE(reassigned == naive_copy) << firstDifference(reassigned, naive_copy);
    OccupancyGrid assigned(res);
    assigned.setSimd(simd);
    both(assigned, scratch);
    assigned = reassigned;
    OccupancyGrid assigned_naive = naive_copy;
    for (int i = 0; i < 30; ++i)
      both(assigned, assigned_naive);
    EXPECT_TRUE(assigned == assigned_naive) << firstDifference(assigned, assigned_naive);
  }
}

TEST(OccupancyGrid, CopiesKeepIntegratingLikeTheNaiveReference) {
  // integrateSonar keeps scratch buffers (rows, a tile table) between calls: a copy must not
  // share them, and cones of very different sizes one after another must not see stale entries.
  std::mt19937_64 rng(99);
  SonarInverseModel model;
  OccupancyGrid fast(0.01), naive(0.01);
  for (int i = 0; i < 40; ++i) {
    const RandomCone c = randomCone(rng, i % 2 == 0 ? 3.0 : 0.2);
    fast.integrateSonar(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
    naive.integrateSonarNaive(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
  }
  OccupancyGrid fast_copy = fast;
  OccupancyGrid naive_copy = naive;
  for (int i = 0; i < 40; ++i) {
    const RandomCone c = randomCone(rng, 1.0);
    const RandomCone d = randomCone(rng, 2.0);
    fast.integrateSonar(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
    naive.integrateSonarNaive(c.origin, c.heading_rad, c.beam_rad, c.range_m, c.echo, model);
    fast_copy.integrateSonar(d.origin, d.heading_rad, d.beam_rad, d.range_m, d.echo, model);
    naive_copy.integrateSonarNaive(d.origin, d.heading_rad, d.beam_rad, d.range_m, d.echo, model);
  }
  EXPECT_TRUE(fast == naive) << firstDifference(fast, naive);
  EXPECT_TRUE(fast_copy == naive_copy) << firstDifference(fast_copy, naive_copy);
  EXPECT_FALSE(fast == fast_copy);
  OccupancyGrid assigned(0.01);
  assigned = fast_copy;
  const RandomCone e = randomCone(rng, 1.0);
  assigned.integrateSonar(e.origin, e.heading_rad, e.beam_rad, e.range_m, e.echo, model);
  naive_copy.integrateSonarNaive(e.origin, e.heading_rad, e.beam_rad, e.range_m, e.echo, model);
  EXPECT_TRUE(assigned == naive_copy) << firstDifference(assigned, naive_copy);
}

}  // namespace
}  // namespace irgs
