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

CellZones fromRows(const std::vector<ConeRow>& rows) {
  CellZones cells;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const ConeRow& r = rows[k];
    EXPECT_LE(r.col0, r.col1) << "row " << r.row;
    if (k > 0) {
      EXPECT_GT(r.row, rows[k - 1].row);
    }
    if (r.hasFree()) {
      EXPECT_GE(r.free0, r.col0) << "row " << r.row;
      EXPECT_LE(r.free1, r.col1) << "row " << r.row;
    }
    for (int col = r.col0; col <= r.col1; ++col) {
      const bool free = col >= r.free0 && col <= r.free1;
      cells.emplace(std::pair{col, r.row}, free ? ConeZone::kFree : ConeZone::kOccupied);
    }
  }
  return cells;
}

TEST(SonarCone, RowsMatchPerCellCriterionOnRandomCones) {
  // The row scan confirms each analytic boundary with two evaluations and walks only when
  // rounding moved it: random apexes far from the origin, every heading, 1 cm cells.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ConeRow> rows;
  for (int i = 0; i < 250; ++i) {
    SonarInverseModel model;
    model.arc_thickness_m = 0.1 * unit(rng);
    const Vec2 apex(-300.0 + 600.0 * unit(rng), -300.0 + 600.0 * unit(rng));
    const SonarCone cone =
        makeSonarCone(apex, 2.0 * kPi * unit(rng), degToRad(2.0 + 170.0 * unit(rng)),
                      1.5 * unit(rng), unit(rng) < 0.7, model);
    const CellZones expected = perCell(cone, 0.01);
    for (const GridSimd simd : {GridSimd::kPortable, GridSimd::kAvx2, GridSimd::kAvx512}) {
      if (!gridSimdSupported(simd))
        continue;
      scanConeRows(cone, 0.01, rows, simd);
      ASSERT_EQ(fromRows(rows), expected) << "cone " << i << " simd " << static_cast<int>(simd);
    }
  }
}

TEST(SonarCone, RowsMatchPerCellCriterionWhenBoundariesPassThroughCellCentres) {
  // Apex on a cell centre, edges along the grid's diagonals and axes, radii whole numbers of
  // cells: every boundary estimate falls on (or within rounding of) a cell centre, where the
  // scan must not trust the estimate but evaluate the criterion. Near and far from the origin.
  std::vector<ConeRow> rows;
  const double res = 0.01;
  for (const double far : {0.0, 1234.5, -98765.4}) {
    for (int h = 0; h < 16; ++h) {
      for (const int radius_cells : {7, 20, 53}) {
        const Vec2 apex(cellCentreCoordinate(17, res) + far, cellCentreCoordinate(-4, res) - far);
        SonarInverseModel model;
        model.arc_thickness_m = 4.0 * res;
        const SonarCone cone =
            makeSonarCone(apex, h * kPi / 8.0, kPi / 2.0, radius_cells * res, h % 2 == 0, model);
        scanConeRows(cone, res, rows);
        ASSERT_EQ(fromRows(rows), perCell(cone, res))
            << "far " << far << " heading " << h << " radius " << radius_cells;
      }
    }
  }
}

TEST(SonarCone, ExactPathAloneMatchesPerCellCriterionAndTheFastScan) {
  // scanConeRows decides most rows from the vectorised estimates and hands the others to the
  // exact per-row path; on random cones the second sees few rows. Here it scans every row, on
  // the same kind of cones as above and on the sizes the grid benchmark uses.
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ConeRow> exact, fast;
  for (int i = 0; i < 300; ++i) {
    SonarInverseModel model;
    model.arc_thickness_m = 0.1 * unit(rng);
    const double far = i % 2 == 0 ? 3.0 : 3000.0;
    const Vec2 apex(-far + 2.0 * far * unit(rng), -far + 2.0 * far * unit(rng));
    const double range = i % 4 == 0 ? 3.0 * unit(rng) : 0.5 * unit(rng);
    const SonarCone cone =
        makeSonarCone(apex, 2.0 * kPi * unit(rng), degToRad(2.0 + 90.0 * unit(rng)), range,
                      unit(rng) < 0.7, model);
    scanConeRowsExact(cone, 0.01, exact);
    ASSERT_EQ(fromRows(exact), perCell(cone, 0.01)) << "cone " << i;
    for (const GridSimd simd : {GridSimd::kPortable, GridSimd::kAvx2, GridSimd::kAvx512}) {
      if (!gridSimdSupported(simd))
        continue;
      scanConeRows(cone, 0.01, fast, simd);
      ASSERT_EQ(fromRows(fast), fromRows(exact))
          << "cone " << i << " simd " << static_cast<int>(simd);
    }
  }
}

TEST(SonarCone, SpansMatchPerCellCriterionWhenAnEdgeIsNearlyAxisAligned) {
  // An edge within a hair of horizontal crosses a row at a column far from any estimate's
  // reach (its slope in columns per row is huge or infinite): the scan must fall back to
  // walking and still agree with the criterion. Vertical edges are the other extreme.
  const double res = 0.05;
  const double beam = degToRad(30.0);
  std::vector<ConeSpan> spans;
  int cones = 0;
  for (const double axis : {0.0, 0.5 * kPi, kPi, -0.5 * kPi})
    for (const double hair : {0.0, 1e-15, -1e-15, 1e-9, -1e-9, 1e-5})
      for (const double side : {-1.0, 1.0})
        for (const Vec2& apex : {Vec2(0.0, 0.0), Vec2(0.025, 0.025), Vec2(0.31, -0.17)}) {
          const double heading = axis + side * 0.5 * beam + hair;
          const SonarCone cone = makeSonarCone(apex, heading, beam, 1.2, true, {});
          rasteriseCone(cone, res, spans);
          ASSERT_EQ(fromSpans(spans), perCell(cone, res))
              << "heading " << heading << " apex (" << apex.x() << ", " << apex.y() << ")";
          ++cones;
        }
  EXPECT_EQ(cones, 4 * 6 * 2 * 3);
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
