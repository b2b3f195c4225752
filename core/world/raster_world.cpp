#include "core/world/raster_world.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

namespace irgs {
namespace {

// Stand-in for "no blocking cell in this row/column" that keeps the parabola arithmetic finite.
constexpr double kFar = 1e20;

// One-dimensional squared Euclidean distance transform of sampled function f (Felzenszwalb &
// Huttenlocher 2012, "Distance Transforms of Sampled Functions", algorithm DT). Transforms
// grid[first + i * stride] for i < n in place. v, z are scratch of sizes n and n + 1.
void distanceTransform1d(std::vector<double>& grid, std::size_t first, std::size_t stride,
                         std::size_t n, std::vector<double>& f, std::vector<std::size_t>& v,
                         std::vector<double>& z) {
  for (std::size_t i = 0; i < n; ++i)
    f[i] = grid[first + i * stride];
  std::size_t k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  // z[0] = -inf stops the loop below at k = 0: f is finite, so s is too.
  const auto intersection = [&f, &v](std::size_t q, std::size_t j) {
    const auto qd = static_cast<double>(q), vj = static_cast<double>(v[j]);
    return ((f[q] + qd * qd) - (f[v[j]] + vj * vj)) / (2.0 * qd - 2.0 * vj);
  };
  for (std::size_t q = 1; q < n; ++q) {
    double s = intersection(q, k);
    while (s <= z[k]) {
      --k;
      s = intersection(q, k);
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (std::size_t q = 0; q < n; ++q) {
    const auto qd = static_cast<double>(q);
    while (z[k + 1] < qd)
      ++k;
    const double dq = qd - static_cast<double>(v[k]);
    grid[first + q * stride] = dq * dq + f[v[k]];
  }
}

}  // namespace

StartPoseSearch findStartPose(const RasterMap& raster, double clearance_m) {
  StartPoseSearch result;
  if (raster.empty() || raster.cells.size() != static_cast<std::size_t>(raster.width) *
                                                   static_cast<std::size_t>(raster.height)) {
    return result;
  }
  const auto w = static_cast<std::size_t>(raster.width);
  const auto h = static_cast<std::size_t>(raster.height);

  // Squared distance (in cells, centre to centre) to the nearest blocking cell.
  std::vector<double> d2(w * h);
  for (std::size_t i = 0; i < d2.size(); ++i)
    d2[i] = isFreeCell(raster.cells[i]) ? kFar : 0.0;
  {
    const std::size_t n = std::max(w, h);
    std::vector<double> f(n), z(n + 1);
    std::vector<std::size_t> v(n);
    for (std::size_t row = 0; row < h; ++row)
      distanceTransform1d(d2, row * w, 1, w, f, v, z);
    for (std::size_t col = 0; col < w; ++col)
      distanceTransform1d(d2, col, w, h, f, v, z);
  }

  const double res = raster.resolution_m;
  bool have_best = false, have_fallback = false;
  std::size_t best = 0, fallback = 0;
  double best_origin_d2 = 0.0, fallback_clearance = -1.0;
  for (std::size_t row = 0; row < h; ++row) {
    for (std::size_t col = 0; col < w; ++col) {
      const std::size_t i = row * w + col;
      if (!isFreeCell(raster.cells[i]))
        continue;
      // Centre to the nearest blocking cell's edge, and to the raster edge, in cells.
      const double to_blocked =
          d2[i] >= kFar * 0.5 ? std::numeric_limits<double>::infinity() : std::sqrt(d2[i]) - 0.5;
      const double to_edge =
          std::min({static_cast<double>(col) + 0.5, static_cast<double>(w - col) - 0.5,
                    static_cast<double>(row) + 0.5, static_cast<double>(h - row) - 0.5});
      const double clearance = std::min(to_blocked, to_edge) * res;
      if (clearance >= clearance_m) {
        const Vec2 c = raster.cellCentre(static_cast<int>(col), static_cast<int>(row));
        const double od2 = c.squaredNorm();
        if (!have_best || od2 < best_origin_d2) {
          have_best = true;
          best = i;
          best_origin_d2 = od2;
          result.clearance_m = clearance;
        }
      } else if (!have_best && clearance > fallback_clearance) {
        have_fallback = true;
        fallback = i;
        fallback_clearance = clearance;
      }
    }
  }
  const auto poseOf = [&](std::size_t i) {
    const Vec2 c = raster.cellCentre(static_cast<int>(i % w), static_cast<int>(i / w));
    return Pose2{c.x(), c.y(), 0.0};
  };
  if (have_best) {
    result.found = true;
    result.pose = poseOf(best);
  } else if (have_fallback) {
    result.pose = poseOf(fallback);
    result.clearance_m = fallback_clearance;
  } else {
    const Box2 b = raster.bounds();
    const Vec2 centre = 0.5 * (b.min + b.max);
    result.pose = {centre.x(), centre.y(), 0.0};
  }
  return result;
}

WorldMap worldFromRaster(RasterMap raster, const std::string& source, double clearance_m,
                         StartPoseSearch* search) {
  WorldMap world;
  world.name = std::filesystem::path(source).stem().string();
  const StartPoseSearch found = findStartPose(raster, clearance_m);
  world.start = found.pose;
  if (search != nullptr)
    *search = found;
  world.raster = RasterLayer{source, std::move(raster)};
  return world;
}

}  // namespace irgs
