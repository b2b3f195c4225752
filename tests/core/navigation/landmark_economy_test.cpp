#include "core/navigation/landmark_economy.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace irgs {

namespace {

TEST(LandmarkEconomy, OneBlockRingNeedsAMarkerPerSquareMetreOrFourMarkersAndEightLights) {
  // A 4 m block ringed by 2 m corridors: 6 x 6 m outside, 2 x 2 m hole = 32 m^2.
  const EconomyRow row = landmarkEconomy({1, 1, 4.0, 2.0}, EconomyParams{});
  EXPECT_NEAR(row.free_area_m2, 32.0, 1e-9);
  EXPECT_EQ(row.nodes, 4);
  EXPECT_EQ(row.edges, 4);
  EXPECT_EQ(row.artificial_markers, 32);
  EXPECT_EQ(row.mixed_markers, 4);
  EXPECT_EQ(row.mixed_lights, 8);  // 2 m lit per 4 m edge: lights at 1 m and 3 m
}

TEST(LandmarkEconomy, CrossingCorridorsShareMarkersSoTheGapGrowsWithArea) {
  const EconomyRow small = landmarkEconomy({1, 1, 4.0, 2.0}, EconomyParams{});
  const EconomyRow big = landmarkEconomy({4, 3, 4.0, 2.0}, EconomyParams{});
  EXPECT_GT(big.free_area_m2, small.free_area_m2);
  const int gap_small = small.artificial_markers - small.mixed_markers;
  const int gap_big = big.artificial_markers - big.mixed_markers;
  EXPECT_GT(gap_big, gap_small);
  EXPECT_EQ(big.nodes, 20);
  EXPECT_EQ(big.edges, 31);
  // The 1 m cells line up with the corridors: one marker per square metre, and the squares of a
  // junction count once although two corridors cross there.
  EXPECT_NEAR(big.artificial_markers, big.free_area_m2, 1e-9);
}

TEST(LandmarkEconomy, CoarserMarkerCellsNeedFewerMarkers) {
  EconomyParams coarse;
  coarse.marker_cell_m = 2.0;
  EXPECT_LT(landmarkEconomy({2, 2, 4.0, 2.0}, coarse).artificial_markers,
            landmarkEconomy({2, 2, 4.0, 2.0}, EconomyParams{}).artificial_markers);
}

TEST(LandmarkEconomy, RefusesAnEmptyFloor) {
  EXPECT_THROW(landmarkEconomy({0, 1, 4.0, 2.0}, EconomyParams{}), std::invalid_argument);
  EXPECT_THROW(landmarkEconomy({1, 1, 2.0, 2.0}, EconomyParams{}), std::invalid_argument);
}

}  // namespace
}  // namespace irgs
