#pragma once
// A uniform-grid spatial index over a fixed set of segments: each cell lists (in ascending
// order) the segments that pass within kMargin_m of it. Used by the indexed ray caster and by
// the collision, clearance and bumper queries.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/geometry/types.hpp"

namespace irgs {

class SegmentGrid {
 public:
  // Registration is conservative by this much so floating-point rounding at cell borders can
  // never hide a segment from a query.
  static constexpr double kMargin_m = 1e-6;
  static constexpr double kDefaultCellSize_m = 0.5;
  static constexpr std::int64_t kMaxCells = std::int64_t{1} << 22;

  SegmentGrid() = default;
  // cell_size_m <= 0 picks kDefaultCellSize_m, enlarged if the grid would exceed kMaxCells.
  explicit SegmentGrid(std::vector<Segment> segments, double cell_size_m = 0.0);

  const std::vector<Segment>& segments() const { return segments_; }
  bool empty() const { return segments_.empty(); }
  double cellSize() const { return cell_; }
  int cols() const { return cols_; }
  int rows() const { return rows_; }
  const Box2& bounds() const { return bounds_; }

  // Segments registered in cell (col, row), ascending; the cell must exist.
  std::span<const std::uint32_t> cell(int col, int row) const {
    const std::size_t i = static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) +
                          static_cast<std::size_t>(col);
    return {items_.data() + starts_[i], items_.data() + starts_[i + 1]};
  }
  // Column/row containing coordinate x/y (floor), saturated to [-1, cols] / [-1, rows] so far
  // away or infinite coordinates stay representable. x, y must not be NaN.
  int colOf(double x) const {
    return static_cast<int>(
        std::clamp(std::floor((x - bounds_.min.x()) / cell_), -1.0, static_cast<double>(cols_)));
  }
  int rowOf(double y) const {
    return static_cast<int>(
        std::clamp(std::floor((y - bounds_.min.y()) / cell_), -1.0, static_cast<double>(rows_)));
  }

  // Replaces `out` with every segment registered in a cell overlapping `box`, each once
  // (order unspecified). Not thread-safe: it uses internal scratch marks.
  void gather(const Box2& box, std::vector<std::uint32_t>& out) const;

 private:
  std::vector<Segment> segments_;
  Box2 bounds_;
  double cell_ = kDefaultCellSize_m;
  int cols_ = 0;
  int rows_ = 0;
  std::vector<std::uint32_t> starts_;  // CSR: cell i holds items_[starts_[i] .. starts_[i+1])
  std::vector<std::uint32_t> items_;
  mutable std::vector<std::uint32_t> marks_;  // per segment: last gather that saw it
  mutable std::uint32_t mark_ = 0;
};

}  // namespace irgs
