#include "core/mapping/sonar_cone.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>
#include <vector>

namespace irgs {
namespace {

using CellZones = std::map<std::pair<int, int>, ConeZone>;  // (col, row) -> zone

CellZones fromSpans(const std::vector<ConeSpan>& spans) {
  CellZones cells;
  for (const ConeSpan& s : spans) {
    for (int col = s.col0; col <= s.col1; ++col) {
      const bool inserted = cells.emplace(std::pair{col, s.row}, s.zone).second;
      EXPECT_TRUE(inserted) << "cell (" << col << ", " << s.row << ") in two spans";
    }
  }
  return cells;
}

// Every cell of the bounds (and a margin around them) classified one by one.
CellZones perCell(const SonarCone& cone, double res) {
  CellZones cells;
  const OccupancyGrid::CellRect b = coneCellBounds(cone, res);
  for (int row = b.row0 - 3; row <= b.row1 + 3; ++row)
    for (int col = b.col0 - 3; col <= b.col1 + 3; ++col)
      if (const ConeZone z = cone.classifyCell(col, row, res); z != ConeZone::kOutside)
        cells.emplace(std::pair{col, row}, z);
  return cells;
}

TEST(SonarCone, SpansMatchPerCellCriterionOnDegenerateCones) {
  // Cones built to sit on ties: apex on cell centres and corners, headings along axes and
  // diagonals, beams up to 179 degrees, ranges on whole cells. The rasteriser must still give
  // exactly the cells the criterion accepts, because both round the same way.
  const double res = 0.1;
  const std::vector<Vec2> apexes = {
      {0.0, 0.0}, {0.05, 0.05}, {0.05, 0.0}, {-0.3, 0.25}, {1e3, -1e3}};
  std::vector<double> headings;
  for (int k = -8; k <= 8; ++k)
    headings.push_back(k * kPi / 8.0);
  const std::vector<double> beams = {degToRad(5.0),  degToRad(25.0), degToRad(45.0),
                                     degToRad(60.0), kPi / 2.0,      degToRad(179.0)};
  const std::vector<double> ranges = {0.0, 0.05, 0.1, 0.3, 1.0};
  SonarInverseModel model;
  model.arc_thickness_m = 0.1;
  std::vector<ConeSpan> spans;
  int cones = 0;
  for (const Vec2& apex : apexes)
    for (const double h : headings)
      for (const double beam : beams)
        for (const double range : ranges)
          for (const bool echo : {true, false}) {
            const SonarCone cone = makeSonarCone(apex, h, beam, range, echo, model);
            rasteriseCone(cone, res, spans);
            ASSERT_EQ(fromSpans(spans), perCell(cone, res))
                << "apex (" << apex.x() << ", " << apex.y() << ") heading " << h << " beam " << beam
                << " range " << range << " echo " << echo;
            ++cones;
          }
  EXPECT_EQ(cones, 5 * 17 * 6 * 5 * 2);
}

TEST(SonarCone, SpansAreOrderedDisjointAndNeverOutside) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ConeSpan> spans;
  for (int i = 0; i < 200; ++i) {
    const SonarCone cone =
        makeSonarCone({unit(rng), unit(rng)}, 10.0 * unit(rng), degToRad(5.0 + 55.0 * unit(rng)),
                      2.0 * unit(rng), unit(rng) < 0.5, {});
    rasteriseCone(cone, 0.01, spans);
    for (std::size_t k = 0; k < spans.size(); ++k) {
      ASSERT_NE(spans[k].zone, ConeZone::kOutside);
      ASSERT_LE(spans[k].col0, spans[k].col1);
      if (k > 0) {
        ASSERT_GE(spans[k].row, spans[k - 1].row);
      }
      if (k > 0 && spans[k].row == spans[k - 1].row) {
        ASSERT_GT(spans[k].col0, spans[k - 1].col1);
      }
    }
    ASSERT_EQ(fromSpans(spans), perCell(cone, 0.01));
  }
}

TEST(SonarCone, CriterionPutsArcBandBetweenFreeAndOuterRadius) {
  SonarInverseModel model;
  model.arc_thickness_m = 0.2;
  const SonarCone cone = makeSonarCone({0.0, 0.0}, 0.0, degToRad(20.0), 1.0, true, model);
  EXPECT_EQ(cone.classify(0.89, 0.0), ConeZone::kFree);
  EXPECT_EQ(cone.classify(0.9, 0.0), ConeZone::kOccupied);  // r_free itself is occupied
  EXPECT_EQ(cone.classify(1.1, 0.0), ConeZone::kOccupied);  // and so is r_outer
  EXPECT_EQ(cone.classify(1.11, 0.0), ConeZone::kOutside);
  EXPECT_EQ(cone.classify(0.5, 0.5 * std::tan(degToRad(9.0))), ConeZone::kFree);
  EXPECT_EQ(cone.classify(0.5, 0.5 * std::tan(degToRad(11.0))), ConeZone::kOutside);
  EXPECT_EQ(cone.classify(-0.5, 0.0), ConeZone::kOutside);  // not the opposite wedge
  EXPECT_EQ(cone.classifyWithAngles(0.89, 0.0), ConeZone::kFree);
  EXPECT_EQ(cone.classifyWithAngles(1.0, 0.1), ConeZone::kOccupied);
  EXPECT_EQ(cone.classifyWithAngles(-0.5, 0.0), ConeZone::kOutside);
}

TEST(SonarCone, NoEchoConeWithZeroFreeRangeHasNoCells) {
  SonarInverseModel model;
  model.no_echo_free_range_m = 0.0;
  std::vector<ConeSpan> spans{{1, 2, 3, ConeZone::kFree}};
  rasteriseCone(makeSonarCone({0.0, 0.0}, 0.0, 0.4, 3.0, false, model), 0.01, spans);
  EXPECT_TRUE(spans.empty());
}

}  // namespace
}  // namespace irgs
