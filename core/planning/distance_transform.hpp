#pragma once
// Exact squared Euclidean distance transform on a grid (Felzenszwalb and Huttenlocher, "Distance
// Transforms of Sampled Functions", 2012): two passes of the 1-D lower envelope of parabolas,
// O(cells). Distances are between cell centres, in cells squared.

#include <cstdint>
#include <vector>

namespace irgs {

// For each cell of a width x height row-major grid, the squared distance (in cells²) from its
// centre to the centre of the nearest cell with source[i] != 0; kNoSource when the grid has no
// source. Throws std::invalid_argument when source.size() != width * height or a size < 0.
inline constexpr double kNoSource = 1e300;
std::vector<double> squaredDistanceTransform(const std::vector<std::uint8_t>& source, int width,
                                             int height);

}  // namespace irgs
