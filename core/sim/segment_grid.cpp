#include "core/sim/segment_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace irgs {

namespace {

// Calls f(col, row) for every cell that the segment passes within `margin` of: for each
// column strip, the rows spanned by the part of the segment inside the (widened) strip.
template <class F>
void forEachCellOfSegment(const Segment& s, const Box2& bounds, double cell, int cols, int rows,
                          double margin, F&& f) {
  const Vec2 d = s.b - s.a;
  auto colOf = [&](double x) { return static_cast<int>(std::floor((x - bounds.min.x()) / cell)); };
  auto rowOf = [&](double y) { return static_cast<int>(std::floor((y - bounds.min.y()) / cell)); };
  const int c0 = std::clamp(colOf(std::min(s.a.x(), s.b.x()) - margin), 0, cols - 1);
  const int c1 = std::clamp(colOf(std::max(s.a.x(), s.b.x()) + margin), 0, cols - 1);
  for (int c = c0; c <= c1; ++c) {
    const double x0 = bounds.min.x() + c * cell - margin;
    const double x1 = bounds.min.x() + (c + 1) * cell + margin;
    double t0 = 0.0, t1 = 1.0;
    if (d.x() != 0.0) {
      double ta = (x0 - s.a.x()) / d.x(), tb = (x1 - s.a.x()) / d.x();
      if (ta > tb)
        std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      if (t0 > t1)
        continue;
    }
    const double ya = s.a.y() + t0 * d.y(), yb = s.a.y() + t1 * d.y();
    const int r0 = std::clamp(rowOf(std::min(ya, yb) - margin), 0, rows - 1);
    const int r1 = std::clamp(rowOf(std::max(ya, yb) + margin), 0, rows - 1);
    for (int r = r0; r <= r1; ++r)
      f(c, r);
  }
}

}  // namespace

SegmentGrid::SegmentGrid(std::vector<Segment> segments, double cell_size_m)
    : segments_(std::move(segments)) {
  if (segments_.size() >= std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("SegmentGrid: too many segments");
  for (const Segment& s : segments_) {
    if (!std::isfinite(s.a.x()) || !std::isfinite(s.a.y()) || !std::isfinite(s.b.x()) ||
        !std::isfinite(s.b.y()))
      throw std::invalid_argument("SegmentGrid: segment with a non-finite coordinate");
    bounds_.extend(s.a);
    bounds_.extend(s.b);
  }
  if (segments_.empty())
    return;
  bounds_.min -= Vec2::Constant(kMargin_m);
  bounds_.max += Vec2::Constant(kMargin_m);
  const Vec2 size = bounds_.size();
  cell_ = cell_size_m > 0.0 ? cell_size_m : kDefaultCellSize_m;
  // Enlarge the cells until the grid fits the cell budget.
  while (std::ceil(size.x() / cell_) * std::ceil(size.y() / cell_) > static_cast<double>(kMaxCells))
    cell_ *= 2.0;
  cols_ = std::max(1, static_cast<int>(std::ceil(size.x() / cell_)));
  rows_ = std::max(1, static_cast<int>(std::ceil(size.y() / cell_)));

  const std::size_t n_cells = static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_);
  std::vector<std::uint32_t> counts(n_cells + 1, 0);
  auto index = [&](int c, int r) {
    return static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) +
           static_cast<std::size_t>(c);
  };
  for (const Segment& s : segments_)
    forEachCellOfSegment(s, bounds_, cell_, cols_, rows_, kMargin_m,
                         [&](int c, int r) { ++counts[index(c, r) + 1]; });
  for (std::size_t i = 1; i <= n_cells; ++i)
    counts[i] += counts[i - 1];
  starts_ = counts;
  items_.resize(starts_.back());
  std::vector<std::uint32_t> fill(starts_.begin(), starts_.end() - 1);
  for (std::uint32_t k = 0; k < segments_.size(); ++k)
    forEachCellOfSegment(segments_[k], bounds_, cell_, cols_, rows_, kMargin_m,
                         [&](int c, int r) { items_[fill[index(c, r)]++] = k; });
  marks_.assign(segments_.size(), 0);
}

void SegmentGrid::gather(const Box2& box, std::vector<std::uint32_t>& out) const {
  out.clear();
  if (segments_.empty() || box.empty())
    return;
  if (box.max.x() < bounds_.min.x() || box.min.x() > bounds_.max.x() ||
      box.max.y() < bounds_.min.y() || box.min.y() > bounds_.max.y())
    return;
  if (++mark_ == 0) {  // wrapped: clear the stale marks once every 2^32 gathers
    std::fill(marks_.begin(), marks_.end(), 0);
    mark_ = 1;
  }
  const int c0 = std::clamp(colOf(box.min.x()), 0, cols_ - 1);
  const int c1 = std::clamp(colOf(box.max.x()), 0, cols_ - 1);
  const int r0 = std::clamp(rowOf(box.min.y()), 0, rows_ - 1);
  const int r1 = std::clamp(rowOf(box.max.y()), 0, rows_ - 1);
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      for (const std::uint32_t k : cell(c, r)) {
        if (marks_[k] != mark_) {
          marks_[k] = mark_;
          out.push_back(k);
        }
      }
    }
  }
}

}  // namespace irgs
