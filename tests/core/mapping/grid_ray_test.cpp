#include "core/mapping/grid_ray.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <stdexcept>
#include <vector>

namespace irgs {
namespace {

TEST(TraverseRay, VisitsTheLiteralCellsOfAShallowRay) {
  // 1 m cells. From (0.5, 0.5) to (4.5, 2.5): slope 1/2, crossing x = 1, 2, 3, 4 and y = 1, 2.
  // The ray meets y = 1 at x = 1.5 and y = 2 at x = 3.5.
  const std::vector<Cell> expected = {{0, 0}, {1, 0}, {1, 1}, {2, 1}, {3, 1}, {3, 2}, {4, 2}};
  EXPECT_EQ(traverseRay({0.5, 0.5}, {4.5, 2.5}, 1.0), expected);
}

TEST(TraverseRay, WorksInNegativeDirectionsAndAcrossTheOrigin) {
  // From (0.2, 0.3) to (-1.8, -0.7) with 1 m cells: x crosses 0 and -1, y crosses 0 at
  // x = -0.4 (t = 0.3), between the two x crossings (t = 0.1, 0.6).
  const std::vector<Cell> expected = {{0, 0}, {-1, 0}, {-1, -1}, {-2, -1}};
  EXPECT_EQ(traverseRay({0.2, 0.3}, {-1.8, -0.7}, 1.0), expected);
}

TEST(TraverseRay, AxisAlignedAndDegenerateRays) {
  EXPECT_EQ(traverseRay({0.05, 0.05}, {0.35, 0.05}, 0.1),
            (std::vector<Cell>{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(traverseRay({0.05, 0.05}, {0.05, -0.15}, 0.1),
            (std::vector<Cell>{{0, 0}, {0, -1}, {0, -2}}));
  EXPECT_EQ(traverseRay({0.05, 0.05}, {0.05, 0.05}, 0.1), (std::vector<Cell>{{0, 0}}));
  // Through a corner exactly: x first.
  EXPECT_EQ(traverseRay({0.5, 0.5}, {1.5, 1.5}, 1.0), (std::vector<Cell>{{0, 0}, {1, 0}, {1, 1}}));
}

TEST(TraverseRay, RandomRaysAreFourConnectedAndEndInTheEndCell) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(-3.0, 3.0);
  const OccupancyGrid frame(0.07);
  for (int i = 0; i < 500; ++i) {
    const Vec2 a(coord(rng), coord(rng)), b(coord(rng), coord(rng));
    const std::vector<Cell> cells = traverseRay(a, b, 0.07);
    ASSERT_EQ(cells.front(), frame.cellAt(a));
    ASSERT_EQ(cells.back(), frame.cellAt(b));
    for (std::size_t k = 1; k < cells.size(); ++k)
      ASSERT_EQ(
          std::abs(cells[k].col - cells[k - 1].col) + std::abs(cells[k].row - cells[k - 1].row), 1);
    // Every visited cell is really crossed: its centre is within half a diagonal of the line.
    const Vec2 d = (b - a).normalized();
    for (const Cell& c : cells) {
      const Vec2 centre = frame.cellCentre(c);
      ASSERT_LE(std::abs(cross(d, centre - a)), 0.07 * std::sqrt(0.5) + 1e-9);
    }
  }
}

TEST(TraverseRay, RejectsBadInput) {
  EXPECT_THROW(traverseRay({0.0, 0.0}, {1.0, 1.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(traverseRay({std::nan(""), 0.0}, {1.0, 1.0}, 0.1), std::invalid_argument);
  EXPECT_THROW(traverseRay({0.0, 0.0}, {1e6, 1e6}, 0.01), std::length_error);
}

}  // namespace
}  // namespace irgs
