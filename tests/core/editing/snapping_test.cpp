#include "core/editing/snapping.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace irgs::editing {
namespace {

TEST(Snapping, GridRoundsToTheNearestStep) {
  SnapSettings s;
  s.grid_step_m = 0.25;
  const SnapResult r = snapPoint(Vec2(1.13, -0.37), s, {});
  EXPECT_EQ(r.kind, SnapKind::kGrid);
  EXPECT_NEAR(r.point.x(), 1.25, 1e-12);
  EXPECT_NEAR(r.point.y(), -0.25, 1e-12);
}

TEST(Snapping, AnEndpointWithinItsRadiusBeatsTheGrid) {
  SnapSettings s;
  s.grid_step_m = 0.5;
  s.endpoint_radius_m = 0.1;
  const std::vector<Vec2> targets = {Vec2(1.03, 2.07), Vec2(5, 5)};
  const SnapResult r = snapPoint(Vec2(1.1, 2.0), s, targets, Vec2(0, 0));
  EXPECT_EQ(r.kind, SnapKind::kEndpoint);
  EXPECT_EQ(r.point, Vec2(1.03, 2.07));
  // Outside the radius: the grid.
  EXPECT_EQ(snapPoint(Vec2(1.3, 2.0), s, targets).kind, SnapKind::kGrid);
}

TEST(Snapping, AngleSnapRoundsTheDirectionFromTheAnchorToTheStep) {
  SnapSettings s;
  s.grid_step_m = 0.1;
  s.endpoints = false;
  s.angle_step_rad = degToRad(45.0);
  const Vec2 anchor(1.0, 1.0);
  // 40 degrees, 1.43 m from the anchor -> 45 degrees, 1.4 m.
  const Vec2 raw = anchor + 1.43 * Vec2(std::cos(degToRad(40)), std::sin(degToRad(40)));
  const SnapResult r = snapPoint(raw, s, {}, anchor);
  EXPECT_EQ(r.kind, SnapKind::kAngle);
  const Vec2 d = r.point - anchor;
  EXPECT_NEAR(std::atan2(d.y(), d.x()), degToRad(45.0), 1e-12);
  EXPECT_NEAR(d.norm(), 1.4, 1e-12);
}

TEST(Snapping, FifteenAndNinetyDegreeStepsSnapToTheirMultiples) {
  SnapSettings s;
  s.grid = false;
  s.endpoints = false;
  for (double step : {15.0, 90.0}) {
    s.angle_step_rad = degToRad(step);
    const Vec2 raw(std::cos(degToRad(97.0)), std::sin(degToRad(97.0)));
    const Vec2 p = snapPoint(raw, s, {}, Vec2::Zero()).point;
    const double deg = radToDeg(std::atan2(p.y(), p.x()));
    EXPECT_NEAR(deg, step * std::round(97.0 / step), 1e-9) << step;
    EXPECT_NEAR(p.norm(), 1.0, 1e-12);  // no grid: the length is kept
  }
}

TEST(Snapping, EverythingOffReturnsTheRawPoint) {
  SnapSettings s;
  s.grid = false;
  s.endpoints = false;
  const SnapResult r = snapPoint(Vec2(0.123, 4.567), s, {Vec2(0.12, 4.56)});
  EXPECT_EQ(r.kind, SnapKind::kNone);
  EXPECT_EQ(r.point, Vec2(0.123, 4.567));
}

TEST(Snapping, BadSettingsThrowAndNonFinitePointsPassThrough) {
  SnapSettings s;
  s.grid_step_m = 0.0;
  EXPECT_THROW(snapPoint(Vec2(0, 0), s, {}), std::invalid_argument);
  s.grid_step_m = 0.1;
  s.angle_step_rad = -1.0;
  EXPECT_THROW(snapPoint(Vec2(0, 0), s, {}), std::invalid_argument);
  s.angle_step_rad = 0.0;
  const Vec2 nan(std::nan(""), 0.0);
  EXPECT_EQ(snapPoint(nan, s, {}).kind, SnapKind::kNone);
}

TEST(Snapping, TargetsLeaveOutExcludedElements) {
  WorldMap map;
  Wall w;
  w.points = {Vec2(0, 0), Vec2(1, 0)};
  map.walls.push_back(w);
  map.start = Pose2{3, 3, 0};
  EXPECT_EQ(snapTargets(map).size(), 3u);
  EXPECT_EQ(snapTargets(map, {{ElementKind::kWall, 0}}).size(), 1u);
}

}  // namespace
}  // namespace irgs::editing
