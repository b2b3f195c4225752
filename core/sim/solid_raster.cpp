#include "core/sim/solid_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/geometry/geometry_queries.hpp"

namespace irgs {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFar = 1e20;  // "no solid cell" in the squared distance transform
// Skip empty space only when the jump is worth re-initialising the walk (>= 2.5 cells).
constexpr double kSkipMinCells = 4.0;

// One-dimensional squared Euclidean distance transform (Felzenszwalb & Huttenlocher 2012,
// "Distance Transforms of Sampled Functions", algorithm DT(f)): d[q] = min_p (q - p)² + f[p].
void distanceTransform1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v,
                         std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  int k = 0;
  v[0] = 0;
  z[0] = -kInf;
  z[1] = kInf;
  auto su = [&](int q, int p) {
    return ((f[static_cast<std::size_t>(q)] + q * static_cast<double>(q)) -
            (f[static_cast<std::size_t>(p)] + p * static_cast<double>(p))) /
           (2.0 * q - 2.0 * p);
  };
  for (int q = 1; q < n; ++q) {
    double s = su(q, v[static_cast<std::size_t>(k)]);
    while (s <= z[static_cast<std::size_t>(k)]) {
      --k;
      s = su(q, v[static_cast<std::size_t>(k)]);
    }
    ++k;
    v[static_cast<std::size_t>(k)] = q;
    z[static_cast<std::size_t>(k)] = s;
    z[static_cast<std::size_t>(k) + 1] = kInf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[static_cast<std::size_t>(k) + 1] < q)
      ++k;
    const int p = v[static_cast<std::size_t>(k)];
    d[static_cast<std::size_t>(q)] =
        (q - p) * static_cast<double>(q - p) + f[static_cast<std::size_t>(p)];
  }
}

}  // namespace

SolidRaster::SolidRaster(const RasterMap& raster, RasterSolidity solidity)
    : width_(raster.width),
      height_(raster.height),
      res_(raster.resolution_m),
      origin_(raster.origin.x, raster.origin.y) {
  if (raster.empty())
    throw std::invalid_argument("SolidRaster: empty raster");
  if (!(res_ > 0.0) || !std::isfinite(res_) || !std::isfinite(origin_.x()) ||
      !std::isfinite(origin_.y()))
    throw std::invalid_argument(
        "SolidRaster: resolution and origin must be finite, resolution > 0");
  const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  if (raster.cells.size() != n)
    throw std::invalid_argument("SolidRaster: cell count does not match width * height");
  solid_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int v = raster.cells[i];
    solid_[i] = (v >= solidity.occupied_threshold || (v < 0 && solidity.unknown_is_solid)) ? 1 : 0;
  }
  computeDistanceTransform();
}

void SolidRaster::computeDistanceTransform() {
  const std::size_t w = static_cast<std::size_t>(width_), h = static_cast<std::size_t>(height_);
  std::vector<double> sq(w * h);
  const std::size_t longest = std::max(w, h);
  std::vector<double> f(longest), d(longest), z(longest + 1);
  std::vector<int> v(longest);
  // Columns first, then rows (the transform is separable).
  f.resize(h);
  d.resize(h);
  for (std::size_t c = 0; c < w; ++c) {
    for (std::size_t r = 0; r < h; ++r)
      f[r] = solid_[r * w + c] ? 0.0 : kFar;
    distanceTransform1d(f, d, v, z);
    for (std::size_t r = 0; r < h; ++r)
      sq[r * w + c] = d[r];
  }
  f.resize(w);
  d.resize(w);
  distance_cells_.resize(w * h);
  for (std::size_t r = 0; r < h; ++r) {
    for (std::size_t c = 0; c < w; ++c)
      f[c] = sq[r * w + c];
    distanceTransform1d(f, d, v, z);
    for (std::size_t c = 0; c < w; ++c)
      distance_cells_[r * w + c] = static_cast<float>(std::sqrt(std::min(d[c], kFar)));
  }
}

Box2 SolidRaster::cellBox(int col, int row) const {
  Box2 b;
  b.min = origin_ + Vec2(col * res_, row * res_);
  b.max = origin_ + Vec2((col + 1) * res_, (row + 1) * res_);
  return b;
}

Vec2 SolidRaster::surfaceNormal(int col, int row, const Vec2& face_normal,
                                const Vec2& direction) const {
  // Sobel gradient of solidity over the 3x3 neighbourhood; the surface normal points down the
  // gradient (from solid to free). On a staircase of cells this recovers the wall's slant, which
  // the face the ray entered cannot (a 45 degree wall would otherwise look axis-aligned).
  auto s = [&](int dc, int dr) { return solid(col + dc, row + dr) ? 1.0 : 0.0; };
  const double gx = (s(1, -1) + 2.0 * s(1, 0) + s(1, 1)) - (s(-1, -1) + 2.0 * s(-1, 0) + s(-1, 1));
  const double gy = (s(-1, 1) + 2.0 * s(0, 1) + s(1, 1)) - (s(-1, -1) + 2.0 * s(0, -1) + s(1, -1));
  Vec2 n(-gx, -gy);
  const double len = n.norm();
  if (len == 0.0)
    return face_normal;
  n /= len;
  // A gradient disagreeing with the face the ray entered, or facing away from the ray (thin
  // structures, corners, isolated cells), is less trustworthy than that face.
  return n.dot(face_normal) > 0.0 && n.dot(direction) < 0.0 ? n : face_normal;
}

std::optional<RayHit> SolidRaster::cast(const Vec2& origin, const Vec2& direction,
                                        double max_range_m) const {
  if (!(max_range_m >= 0.0))
    return std::nullopt;
  // Cell coordinates of the origin; the ray is f + t * direction / res.
  const double fx = (origin.x() - origin_.x()) / res_;
  const double fy = (origin.y() - origin_.y()) / res_;
  const double size[2] = {static_cast<double>(width_), static_cast<double>(height_)};
  const double f[2] = {fx, fy};
  double t_lo = 0.0, t_hi = max_range_m;
  int entry_axis = -1;  // the axis whose face the ray entered the raster through
  for (int axis = 0; axis < 2; ++axis) {
    const double d = direction[axis];
    if (d == 0.0) {
      if (f[axis] < 0.0 || f[axis] >= size[axis])
        return std::nullopt;
      continue;
    }
    double ta = (0.0 - f[axis]) * res_ / d, tb = (size[axis] - f[axis]) * res_ / d;
    if (ta > tb)
      std::swap(ta, tb);
    if (ta > t_lo) {
      t_lo = ta;
      entry_axis = axis;
    }
    t_hi = std::min(t_hi, tb);
  }
  if (t_lo > t_hi)
    return std::nullopt;

  const int step_c = direction.x() > 0.0 ? 1 : -1;
  const int step_r = direction.y() > 0.0 ? 1 : -1;
  const double px = fx + t_lo * direction.x() / res_, py = fy + t_lo * direction.y() / res_;
  int col = std::clamp(static_cast<int>(std::floor(px)), 0, width_ - 1);
  int row = std::clamp(static_cast<int>(std::floor(py)), 0, height_ - 1);
  double t_max_c =
      direction.x() != 0.0 ? ((col + (step_c > 0 ? 1 : 0)) - fx) * res_ / direction.x() : kInf;
  double t_max_r =
      direction.y() != 0.0 ? ((row + (step_r > 0 ? 1 : 0)) - fy) * res_ / direction.y() : kInf;
  const double t_delta_c = direction.x() != 0.0 ? res_ / std::abs(direction.x()) : kInf;
  const double t_delta_r = direction.y() != 0.0 ? res_ / std::abs(direction.y()) : kInf;

  Vec2 face = entry_axis == 0   ? Vec2(static_cast<double>(-step_c), 0.0)
              : entry_axis == 1 ? Vec2(0.0, static_cast<double>(-step_r))
                                : Vec2(-direction);  // origin inside the raster
  double t_enter = t_lo;
  while (true) {
    const std::size_t i = index(col, row);
    if (solid_[i] != 0)
      return RayHit{t_enter, surfaceNormal(col, row, face, direction)};
    // Empty-space skipping: every point of this cell is at least (d - sqrt 2) cells from any
    // solid cell (d = distance transform between cell centres), so the ray can jump ahead by
    // (d - 1.5) cells and restart the walk there. Open floor costs a few jumps instead of a
    // step per cell; the walk near walls, and so every reported hit, is unchanged.
    if (const double d = distance_cells_[i]; d >= kSkipMinCells) {
      t_enter += (d - 1.5) * res_;
      if (t_enter > t_hi)
        return std::nullopt;
      const double qx = fx + t_enter * direction.x() / res_;
      const double qy = fy + t_enter * direction.y() / res_;
      col = std::clamp(static_cast<int>(std::floor(qx)), 0, width_ - 1);
      row = std::clamp(static_cast<int>(std::floor(qy)), 0, height_ - 1);
      if (direction.x() != 0.0)
        t_max_c = ((col + (step_c > 0 ? 1 : 0)) - fx) * res_ / direction.x();
      if (direction.y() != 0.0)
        t_max_r = ((row + (step_r > 0 ? 1 : 0)) - fy) * res_ / direction.y();
      continue;
    }
    if (t_max_c < t_max_r) {
      t_enter = t_max_c;
      t_max_c += t_delta_c;
      col += step_c;
      face = Vec2(static_cast<double>(-step_c), 0.0);
      if (col < 0 || col >= width_)
        return std::nullopt;
    } else {
      t_enter = t_max_r;
      t_max_r += t_delta_r;
      row += step_r;
      face = Vec2(0.0, static_cast<double>(-step_r));
      if (row < 0 || row >= height_)
        return std::nullopt;
    }
    if (t_enter > t_hi)
      return std::nullopt;
  }
}

bool SolidRaster::polygonTouches(std::span<const Vec2> polygon) const {
  if (polygon.empty())
    return false;
  const Box2 box = boundsOf(polygon);
  // One extra cell on each side: touching a cell's border counts. Out-of-range boxes give an
  // empty or clamped range; the exact test below decides.
  auto cellRange = [&](double lo, double hi, double o, int n, int& a, int& b) {
    a = static_cast<int>(std::clamp(std::floor((lo - o) / res_) - 1.0, 0.0, n - 1.0));
    b = static_cast<int>(std::clamp(std::floor((hi - o) / res_) + 1.0, -1.0, n - 1.0));
  };
  int c0 = 0, c1 = 0, r0 = 0, r1 = 0;
  cellRange(box.min.x(), box.max.x(), origin_.x(), width_, c0, c1);
  cellRange(box.min.y(), box.max.y(), origin_.y(), height_, r0, r1);
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      if (solid_[index(c, r)] != 0 && polygonTouchesBox(polygon, cellBox(c, r)))
        return true;
    }
  }
  return false;
}

double SolidRaster::clearanceLowerBound(const Vec2& p, double cap_m) const {
  const double fx = std::floor((p.x() - origin_.x()) / res_);
  const double fy = std::floor((p.y() - origin_.y()) / res_);
  if (fx < 0.0 || fy < 0.0 || fx >= width_ || fy >= height_) {
    // Outside: every solid cell is inside the raster rectangle.
    Box2 rect;
    rect.min = origin_;
    rect.max = origin_ + Vec2(width_ * res_, height_ * res_);
    return std::min(cap_m, pointBoxDistance(p, rect));
  }
  const double centres = distance_cells_[index(static_cast<int>(fx), static_cast<int>(fy))];
  // From p to its cell centre and from the solid cell's centre to its border: res / sqrt(2) each.
  return std::clamp((centres - std::sqrt(2.0)) * res_, 0.0, cap_m);
}

bool SolidRaster::segmentWithin(const Vec2& a, const Vec2& b, double distance_m) const {
  Box2 box;
  box.extend(a);
  box.extend(b);
  box.min -= Vec2::Constant(distance_m + res_);
  box.max += Vec2::Constant(distance_m + res_);
  const int c0 = static_cast<int>(
      std::clamp(std::floor((box.min.x() - origin_.x()) / res_), 0.0, width_ - 1.0));
  const int c1 = static_cast<int>(
      std::clamp(std::floor((box.max.x() - origin_.x()) / res_), -1.0, width_ - 1.0));
  const int r0 = static_cast<int>(
      std::clamp(std::floor((box.min.y() - origin_.y()) / res_), 0.0, height_ - 1.0));
  const int r1 = static_cast<int>(
      std::clamp(std::floor((box.max.y() - origin_.y()) / res_), -1.0, height_ - 1.0));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      if (solid_[index(c, r)] == 0)
        continue;
      Box2 cell = cellBox(c, r);
      cell.min -= Vec2::Constant(distance_m);
      cell.max += Vec2::Constant(distance_m);
      if (segmentIntersectsBox(a, b, cell))
        return true;
    }
  }
  return false;
}

}  // namespace irgs
