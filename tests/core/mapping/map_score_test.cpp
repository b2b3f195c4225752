#include "core/mapping/map_score.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace irgs {
namespace {

// A 4 m x 3 m room of thin walls.
WorldMap room() {
  WorldMap map;
  map.walls.push_back({"room", {{0.0, 0.0}, {4.0, 0.0}, {4.0, 3.0}, {0.0, 3.0}}, true, {}});
  map.start = {2.0, 1.5, 0.0};
  return map;
}

// Marks the walls of room() occupied in a grid by narrow echo cones from 0.3 m inside.
OccupancyGrid perfectGrid(const Vec2& shift = Vec2::Zero()) {
  OccupancyGrid grid(0.01);
  SonarInverseModel model;
  model.occupied_log_odds = 2.0;
  const double beam = degToRad(2.0);
  for (double x = 0.05; x < 4.0; x += 0.01) {
    grid.integrateSonar(Vec2(x, 0.3) + shift, -0.5 * kPi, beam, 0.3, true, model);
    grid.integrateSonar(Vec2(x, 2.7) + shift, 0.5 * kPi, beam, 0.3, true, model);
  }
  for (double y = 0.05; y < 3.0; y += 0.01) {
    grid.integrateSonar(Vec2(0.3, y) + shift, kPi, beam, 0.3, true, model);
    grid.integrateSonar(Vec2(3.7, y) + shift, 0.0, beam, 0.3, true, model);
  }
  return grid;
}

TEST(MapScore, TrueSurfaceIsTheInsideFaceOfTheWalls) {
  const PlanningGrid truth = trueSurfaceGrid(room(), room().start, 0.05);
  // About 2 * (4 + 3) m of wall at 5 cm: ~280 cells.
  EXPECT_GT(truth.blockedCount(), 250u);
  EXPECT_LT(truth.blockedCount(), 320u);
}

TEST(MapScore, AWellBuiltMapScoresNearOne) {
  const MapScore score = scoreMap(perfectGrid(), room(), room().start);
  EXPECT_GT(score.precision, 0.97);
  EXPECT_GT(score.recall, 0.97);
  EXPECT_GT(score.f1, 0.97);
  EXPECT_DOUBLE_EQ(score.resolution_m, 0.05);
}

TEST(MapScore, AMapShiftedBeyondTheToleranceScoresLow) {
  const MapScore score = scoreMap(perfectGrid(Vec2(0.3, 0.3)), room(), room().start);
  EXPECT_LT(score.f1, 0.3);
  // Within the 2-cell (10 cm) tolerance the same map still matches.
  EXPECT_GT(scoreMap(perfectGrid(Vec2(0.06, 0.0)), room(), room().start).f1, 0.9);
}

TEST(MapScore, AnEmptyMapHasZeroRecallAndF1) {
  const MapScore score = scoreMap(OccupancyGrid(0.01), room(), room().start);
  EXPECT_EQ(score.built_cells, 0u);
  EXPECT_EQ(score.recall, 0.0);
  EXPECT_EQ(score.f1, 0.0);
}

TEST(MapScore, RejectsAStartInsideAWallAndBadOptions) {
  Pose2 outside{-5.0, -5.0, 0.0};
  EXPECT_THROW(trueSurfaceGrid(room(), outside, 0.05), std::invalid_argument);
  MapScoreOptions bad;
  bad.tolerance_cells = -1;
  EXPECT_THROW(scoreMap(OccupancyGrid(0.01), room(), room().start, bad), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
