#include "core/sim/ray_caster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace irgs {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Keeps the nearest hit, the lower segment index on exact ties (order independent).
struct Best {
  double t = kInf;
  std::uint32_t index = std::numeric_limits<std::uint32_t>::max();

  void offer(double candidate_t, std::uint32_t k) {
    if (candidate_t < 0.0)
      return;
    if (candidate_t < t || (candidate_t == t && k < index)) {
      t = candidate_t;
      index = k;
    }
  }
  bool found() const { return t < kInf; }
};

std::optional<RayHit> toHit(const Best& best, const PreparedSegments& prepared,
                            const Vec2& direction) {
  if (!best.found())
    return std::nullopt;
  return RayHit{best.t, prepared.normalFacing(best.index, direction)};
}

}  // namespace

void RayCaster::castFan(const Vec2& origin, std::span<const Vec2> directions, double max_range_m,
                        std::span<std::optional<RayHit>> hits) const {
  if (hits.size() != directions.size())
    throw std::invalid_argument("RayCaster::castFan: hits and directions differ in size");
  for (std::size_t i = 0; i < directions.size(); ++i)
    hits[i] = cast(origin, directions[i], max_range_m);
}

PreparedSegments::PreparedSegments(std::span<const Segment> segments) {
  ax_.reserve(segments.size());
  ay_.reserve(segments.size());
  ex_.reserve(segments.size());
  ey_.reserve(segments.size());
  for (const Segment& s : segments) {
    ax_.push_back(s.a.x());
    ay_.push_back(s.a.y());
    ex_.push_back(s.b.x() - s.a.x());
    ey_.push_back(s.b.y() - s.a.y());
  }
}

NaiveSegmentCaster::NaiveSegmentCaster(std::span<const Segment> segments) : prepared_(segments) {}

std::optional<RayHit> NaiveSegmentCaster::cast(const Vec2& origin, const Vec2& direction,
                                               double max_range_m) const {
  Best best;
  const std::size_t n = prepared_.size();
  for (std::size_t k = 0; k < n; ++k)
    best.offer(prepared_.intersect(k, origin, direction, max_range_m),
               static_cast<std::uint32_t>(k));
  return toHit(best, prepared_, direction);
}

GridSegmentCaster::GridSegmentCaster(std::span<const Segment> segments, double cell_size_m)
    : grid_(std::vector<Segment>(segments.begin(), segments.end()), cell_size_m),
      prepared_(segments),
      visited_(segments.size(), 0) {}

std::optional<RayHit> GridSegmentCaster::cast(const Vec2& origin, const Vec2& direction,
                                              double max_range_m) const {
  if (grid_.empty() || !(max_range_m >= 0.0))
    return std::nullopt;
  // Clip the ray to the grid's box (slab method): [t_lo, t_hi].
  const Box2& box = grid_.bounds();
  double t_lo = 0.0, t_hi = max_range_m;
  for (int axis = 0; axis < 2; ++axis) {
    const double o = origin[axis], d = direction[axis];
    if (d == 0.0) {
      if (o < box.min[axis] || o > box.max[axis])
        return std::nullopt;
      continue;
    }
    double ta = (box.min[axis] - o) / d, tb = (box.max[axis] - o) / d;
    if (ta > tb)
      std::swap(ta, tb);
    t_lo = std::max(t_lo, ta);
    t_hi = std::min(t_hi, tb);
  }
  if (t_lo > t_hi)
    return std::nullopt;

  if (++visit_mark_ == 0) {
    std::fill(visited_.begin(), visited_.end(), 0);
    visit_mark_ = 1;
  }
  // Amanatides–Woo traversal from the entry point.
  const double cell = grid_.cellSize();
  const Vec2 entry = origin + t_lo * direction;
  int col = std::clamp(grid_.colOf(entry.x()), 0, grid_.cols() - 1);
  int row = std::clamp(grid_.rowOf(entry.y()), 0, grid_.rows() - 1);
  const int step_c = direction.x() > 0.0 ? 1 : -1;
  const int step_r = direction.y() > 0.0 ? 1 : -1;
  auto boundary = [&](int index, int step, int axis) {
    return box.min[axis] + (step > 0 ? index + 1 : index) * cell;
  };
  double t_max_c =
      direction.x() != 0.0 ? (boundary(col, step_c, 0) - origin.x()) / direction.x() : kInf;
  double t_max_r =
      direction.y() != 0.0 ? (boundary(row, step_r, 1) - origin.y()) / direction.y() : kInf;
  const double t_delta_c = direction.x() != 0.0 ? cell / std::abs(direction.x()) : kInf;
  const double t_delta_r = direction.y() != 0.0 ? cell / std::abs(direction.y()) : kInf;

  Best best;
  while (true) {
    for (const std::uint32_t k : grid_.cell(col, row)) {
      if (visited_[k] == visit_mark_)
        continue;
      visited_[k] = visit_mark_;
      best.offer(prepared_.intersect(k, origin, direction, max_range_m), k);
    }
    const double t_exit = std::min(t_max_c, t_max_r);
    // Every segment not yet seen can only be hit beyond (about) t_exit; continue while a tie or
    // a rounding difference at the cell border is still possible.
    if (best.t + SegmentGrid::kMargin_m < t_exit || t_exit > t_hi + SegmentGrid::kMargin_m)
      break;
    if (t_max_c < t_max_r) {
      col += step_c;
      t_max_c += t_delta_c;
      if (col < 0 || col >= grid_.cols())
        break;
    } else {
      row += step_r;
      t_max_r += t_delta_r;
      if (row < 0 || row >= grid_.rows())
        break;
    }
  }
  return toHit(best, prepared_, direction);
}

void GridSegmentCaster::castFan(const Vec2& origin, std::span<const Vec2> directions,
                                double max_range_m, std::span<std::optional<RayHit>> hits) const {
  if (hits.size() != directions.size())
    throw std::invalid_argument("GridSegmentCaster::castFan: hits and directions differ in size");
  if (!(max_range_m >= 0.0) || grid_.empty()) {
    std::fill(hits.begin(), hits.end(), std::nullopt);
    return;
  }
  // The rays are the whole fan: the box of the origin and the ray ends holds every point any
  // ray can hit, so the segments registered in its cells are all the candidates.
  Box2 box;
  box.extend(origin);
  for (const Vec2& d : directions)
    box.extend(origin + max_range_m * d);
  grid_.gather(box, candidates_);
  for (std::size_t i = 0; i < directions.size(); ++i) {
    Best best;
    for (const std::uint32_t k : candidates_)
      best.offer(prepared_.intersect(k, origin, directions[i], max_range_m), k);
    hits[i] = toHit(best, prepared_, directions[i]);
  }
}

}  // namespace irgs
