#include "core/mapping/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/mapping/sonar_cone.hpp"

// Storage (see docs/decisions/grid.md): 64x64-cell tiles of float log-odds, allocated on the
// first write to any of their cells and found through a hash map on packed tile coordinates.
// NaN marks a never-observed cell, so "observed" costs no extra memory and the update loop
// learns it from the value it loads anyway. A cone update first scans the cone into rows (each
// row: its cells and, within them, the free run; sonar_cone.cpp), prefetching each row's cells as
// the row is found, and then updates each run of equal increments with SSE2 (RunUpdater); tiles
// are looked up once per cone through a small table over the cone's tiles. The row and tile
// buffers are kept between calls, so a warm update allocates nothing.

#if defined(__GNUC__)
#define IRGS_ALWAYS_INLINE __attribute__((always_inline))
#define IRGS_PREFETCH_WRITE(p) __builtin_prefetch((p), 1, 3)
#else
#define IRGS_ALWAYS_INLINE
#define IRGS_PREFETCH_WRITE(p) static_cast<void>(p)
#endif

namespace irgs {
namespace {

constexpr float kUnobserved = std::numeric_limits<float>::quiet_NaN();
constexpr int kTileMask = OccupancyGrid::kTileSize - 1;

// The update of one cell: an unobserved (NaN) cell starts from 0, then delta is added and the
// sum clamped to [lo, hi]. Every path (cone rows, single cells) goes through this expression.
inline float updatedCell(float v, bool unknown, float delta, float lo, float hi) {
  return std::min(std::max((unknown ? 0.0f : v) + delta, lo), hi);
}

// Cone cells are updated by runs: a run is cells [a, b] of one tile row that all get the same
// increment (a row of a cone is at most three runs per tile: occupied, free, occupied). With SSE2
// (every x86-64) a run is whole aligned groups of four cells, the first and last blended with a
// lane mask so that cells outside [a, b] are written back unchanged; elsewhere a plain loop. Both
// compute exactly updatedCell() for each cell (the SSE2 operand order reproduces std::max and
// std::min bit for bit, signed zeros included). The count of cells that were unobserved is
// accumulated per lane and read once per cone.
#if defined(__SSE2__)
class RunUpdater {
 public:
  RunUpdater(float free_delta, float occupied_delta, float lo, float hi)
      : free_(_mm_set1_ps(free_delta)),
        occupied_(_mm_set1_ps(occupied_delta)),
        lo_(_mm_set1_ps(lo)),
        hi_(_mm_set1_ps(hi)) {}

  // Cells [a, b] of the tile row starting at `row` (0 <= a <= b < kTileSize). Groups start at
  // multiples of four cells of the row, so they never leave it.
  IRGS_ALWAYS_INLINE void run(float* row, int a, int b, bool free) {
    const __m128 delta = free ? free_ : occupied_;
    const int g0 = a & ~3;
    const int g1 = b & ~3;
    const __m128 head = headMask(a & 3);
    const __m128 tail = tailMask(b & 3);
    if (g0 == g1) {
      masked(row + g0, delta, _mm_and_ps(head, tail));
      return;
    }
    masked(row + g0, delta, head);
    for (int g = g0 + 4; g < g1; g += 4)
      full(row + g, delta);
    masked(row + g1, delta, tail);
  }

  // Cells that were unobserved, over all runs so far. Each lane counts at most one cell in four
  // of a cone (< 2^31 for any accepted cone), so the 32-bit lanes cannot overflow.
  std::uint64_t fresh() const {
    alignas(16) std::uint32_t lanes[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(lanes), fresh_);
    return std::uint64_t{lanes[0]} + lanes[1] + lanes[2] + lanes[3];
  }

 private:
  // updatedCell() on four lanes: (unknown ? 0 : v) + delta, then std::max(s, lo) = (s < lo) ?
  // lo : s = maxps(lo, s) and std::min(m, hi) = (hi < m) ? hi : m = minps(hi, m).
  IRGS_ALWAYS_INLINE __m128 updated(__m128 v, __m128 unknown, __m128 delta) const {
    const __m128 sum = _mm_add_ps(_mm_andnot_ps(unknown, v), delta);
    return _mm_min_ps(hi_, _mm_max_ps(lo_, sum));
  }
  IRGS_ALWAYS_INLINE void full(float* p, __m128 delta) {
    const __m128 v = _mm_loadu_ps(p);
    const __m128 unknown = _mm_cmpunord_ps(v, v);
    _mm_storeu_ps(p, updated(v, unknown, delta));
    fresh_ = _mm_sub_epi32(fresh_, _mm_castps_si128(unknown));  // a true lane is -1
  }
  IRGS_ALWAYS_INLINE void masked(float* p, __m128 delta, __m128 mask) {
    const __m128 v = _mm_loadu_ps(p);
    const __m128 unknown = _mm_cmpunord_ps(v, v);
    const __m128 n = updated(v, unknown, delta);
    _mm_storeu_ps(p, _mm_or_ps(_mm_and_ps(mask, n), _mm_andnot_ps(mask, v)));
    fresh_ = _mm_sub_epi32(fresh_, _mm_castps_si128(_mm_and_ps(mask, unknown)));
  }
  // Lanes >= k, lanes <= k.
  static __m128 headMask(int k) {
    alignas(16) static constexpr std::int32_t kHead[4][4] = {
        {-1, -1, -1, -1}, {0, -1, -1, -1}, {0, 0, -1, -1}, {0, 0, 0, -1}};
    return _mm_load_ps(reinterpret_cast<const float*>(kHead[k]));
  }
  static __m128 tailMask(int k) {
    alignas(16) static constexpr std::int32_t kTail[4][4] = {
        {-1, 0, 0, 0}, {-1, -1, 0, 0}, {-1, -1, -1, 0}, {-1, -1, -1, -1}};
    return _mm_load_ps(reinterpret_cast<const float*>(kTail[k]));
  }

  __m128 free_, occupied_, lo_, hi_;
  __m128i fresh_ = _mm_setzero_si128();
};
#else
class RunUpdater {
 public:
  RunUpdater(float free_delta, float occupied_delta, float lo, float hi)
      : free_(free_delta), occupied_(occupied_delta), lo_(lo), hi_(hi) {}
  void run(float* row, int a, int b, bool free) {
    const float delta = free ? free_ : occupied_;
    for (int i = a; i <= b; ++i) {
      const bool unknown = std::isnan(row[i]);
      row[i] = updatedCell(row[i], unknown, delta, lo_, hi_);
      fresh_ += unknown ? 1u : 0u;
    }
  }
  std::uint64_t fresh() const { return fresh_; }

 private:
  float free_, occupied_, lo_, hi_;
  std::uint64_t fresh_ = 0;
};
#endif

std::string describe(const Vec2& p) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

}  // namespace

std::optional<std::string> sonarInverseModelError(const SonarInverseModel& model) {
  if (!std::isfinite(model.free_log_odds) || !std::isfinite(model.occupied_log_odds))
    return "log-odds increments must be finite";
  if (!std::isfinite(model.arc_thickness_m) || model.arc_thickness_m < 0.0)
    return "arc_thickness_m must be finite and >= 0";
  if (!std::isfinite(model.clamp_min) || !std::isfinite(model.clamp_max) ||
      model.clamp_min > model.clamp_max)
    return "clamp_min and clamp_max must be finite with clamp_min <= clamp_max";
  if (std::isnan(model.no_echo_free_range_m) || model.no_echo_free_range_m < 0.0)
    return "no_echo_free_range_m must be >= 0";
  return std::nullopt;
}

OccupancyGrid::OccupancyGrid(double resolution_m) : resolution_m_(resolution_m) {
  if (!std::isfinite(resolution_m) || !(resolution_m > 0.0))
    throw std::invalid_argument("OccupancyGrid: resolution_m must be finite and > 0, got " +
                                std::to_string(resolution_m));
}

OccupancyGrid::OccupancyGrid(const OccupancyGrid& other)
    : resolution_m_(other.resolution_m_),
      cell_updates_(other.cell_updates_),
      observed_cells_(other.observed_cells_),
      observed_rect_(other.observed_rect_),
      dirty_rect_(other.dirty_rect_),
      tiles_(other.tiles_),
      tile_index_(other.tile_index_) {}

OccupancyGrid& OccupancyGrid::operator=(const OccupancyGrid& other) {
  if (this != &other) {
    resolution_m_ = other.resolution_m_;
    cell_updates_ = other.cell_updates_;
    observed_cells_ = other.observed_cells_;
    observed_rect_ = other.observed_rect_;
    dirty_rect_ = other.dirty_rect_;
    tiles_ = other.tiles_;
    tile_index_ = other.tile_index_;
  }
  return *this;
}

OccupancyGrid::~OccupancyGrid() = default;

OccupancyGrid::OccupancyGrid(OccupancyGrid&& other) noexcept
    : resolution_m_(other.resolution_m_),
      cell_updates_(std::exchange(other.cell_updates_, 0)),
      observed_cells_(std::exchange(other.observed_cells_, 0)),
      observed_rect_(std::exchange(other.observed_rect_, CellRect{})),
      dirty_rect_(std::exchange(other.dirty_rect_, CellRect{})),
      tiles_(std::move(other.tiles_)),
      tile_index_(std::move(other.tile_index_)) {
  other.tiles_.clear();
  other.tile_index_.clear();
}

OccupancyGrid& OccupancyGrid::operator=(OccupancyGrid&& other) noexcept {
  if (this != &other) {
    resolution_m_ = other.resolution_m_;
    cell_updates_ = std::exchange(other.cell_updates_, 0);
    observed_cells_ = std::exchange(other.observed_cells_, 0);
    observed_rect_ = std::exchange(other.observed_rect_, CellRect{});
    dirty_rect_ = std::exchange(other.dirty_rect_, CellRect{});
    tiles_ = std::move(other.tiles_);
    tile_index_ = std::move(other.tile_index_);
    other.tiles_.clear();
    other.tile_index_.clear();
  }
  return *this;
}

Cell OccupancyGrid::cellAt(const Vec2& p) const {
  const double fx = std::floor(p.x() / resolution_m_);
  const double fy = std::floor(p.y() / resolution_m_);
  constexpr double kLimit = kMaxCellIndex;
  if (!(std::abs(fx) <= kLimit) || !(std::abs(fy) <= kLimit))
    throw std::out_of_range("OccupancyGrid::cellAt: point " + describe(p) +
                            " is not finite or beyond the addressable cells");
  return {static_cast<int>(fx), static_cast<int>(fy)};
}

Vec2 OccupancyGrid::cellCentre(const Cell& c) const {
  return {cellCentreCoordinate(c.col, resolution_m_), cellCentreCoordinate(c.row, resolution_m_)};
}

bool OccupancyGrid::isAddressable(const Vec2& p, double margin_m) const {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(margin_m) || margin_m < 0)
    return false;
  // One spare cell for rounding at the edge.
  const double limit = static_cast<double>(kMaxCellIndex) - 1.0;
  return (std::abs(p.x()) + margin_m) / resolution_m_ < limit &&
         (std::abs(p.y()) + margin_m) / resolution_m_ < limit;
}

OccupancyGrid::TileKey OccupancyGrid::tileKey(int tx, int ty) {
  return (static_cast<TileKey>(static_cast<std::uint32_t>(tx)) << 32) |
         static_cast<TileKey>(static_cast<std::uint32_t>(ty));
}

const float* OccupancyGrid::findTile(int tx, int ty) const {
  const auto it = tile_index_.find(tileKey(tx, ty));
  return it == tile_index_.end() ? nullptr : tiles_[it->second].data();
}

float* OccupancyGrid::findOrCreateTile(int tx, int ty) {
  const auto [it, inserted] =
      tile_index_.try_emplace(tileKey(tx, ty), static_cast<std::uint32_t>(tiles_.size()));
  if (inserted)
    tiles_.emplace_back(static_cast<std::size_t>(kTileCells), kUnobserved);
  return tiles_[it->second].data();
}

float OccupancyGrid::logOdds(const Cell& c) const {
  const float* tile = findTile(c.col >> kTileShift, c.row >> kTileShift);
  if (tile == nullptr)
    return 0.0f;
  const float v = tile[(c.row & kTileMask) * kTileSize + (c.col & kTileMask)];
  return std::isnan(v) ? 0.0f : v;
}

double OccupancyGrid::probability(const Cell& c) const {
  // p = 1 / (1 + exp(-l)): the inverse of l = log(p / (1 - p)).
  return 1.0 / (1.0 + std::exp(-static_cast<double>(logOdds(c))));
}

bool OccupancyGrid::observed(const Cell& c) const {
  const float* tile = findTile(c.col >> kTileShift, c.row >> kTileShift);
  return tile != nullptr &&
         !std::isnan(tile[(c.row & kTileMask) * kTileSize + (c.col & kTileMask)]);
}

IRGS_ALWAYS_INLINE inline float* OccupancyGrid::cachedTile(int tx, int ty) {
  // Tile buffers never move (tiles_ holds them by vector, and growing the outer vector moves the
  // inner ones with their buffers), so the pointers stay valid for the whole cone.
  float*& slot = tile_cache_[static_cast<std::size_t>(ty - cache_ty0_) *
                                 static_cast<std::size_t>(cache_width_) +
                             static_cast<std::size_t>(tx - cache_tx0_)];
  if (slot == nullptr)
    slot = findOrCreateTile(tx, ty);
  return slot;
}

void OccupancyGrid::noteTouched(const CellRect& cells) {
  observed_rect_.extend(cells);
  dirty_rect_.extend(cells);
}

struct OccupancyGrid::ConeUpdater : RunUpdater {
  using RunUpdater::RunUpdater;
};

IRGS_ALWAYS_INLINE inline void OccupancyGrid::applyConeRow(const ConeRow& r, ConeUpdater& u) {
  const int ty = r.row >> kTileShift;
  const int row_offset = (r.row & kTileMask) * kTileSize;
  for (int col = r.col0; col <= r.col1;) {
    const int tx = col >> kTileShift;
    const int base = tx * kTileSize;
    const int run_end = std::min(r.col1, base + kTileMask);
    float* cells = cachedTile(tx, ty) + row_offset;
    // The free run of this piece; empty (f0 > f1) when the row has none or it lies elsewhere.
    const int f0 = std::max(col, r.free0);
    const int f1 = std::min(run_end, r.free1);
    if (f0 > f1) {
      u.run(cells, col - base, run_end - base, false);
    } else {
      if (col < f0)
        u.run(cells, col - base, f0 - 1 - base, false);
      u.run(cells, f0 - base, f1 - base, true);
      if (f1 < run_end)
        u.run(cells, f1 + 1 - base, run_end - base, false);
    }
    col = run_end + 1;
  }
  cell_updates_ += static_cast<std::uint64_t>(r.col1 - r.col0 + 1);
}

IRGS_ALWAYS_INLINE inline void OccupancyGrid::prefetchConeRow(const ConeRow& r) {
  const int ty = r.row >> kTileShift;
  const int row_offset = (r.row & kTileMask) * kTileSize;
  for (int col = r.col0; col <= r.col1;) {
    const int tx = col >> kTileShift;
    const int base = tx * kTileSize;
    const int run_end = std::min(r.col1, base + kTileMask);
    const float* first = cachedTile(tx, ty) + row_offset + (col - base);
    const float* last = first + (run_end - col);
    // The first and last 64-byte lines of [first, last]: the hardware prefetcher follows the
    // stream between them once it has started (prefetching every line cost more than it saved).
    IRGS_PREFETCH_WRITE(first);
    IRGS_PREFETCH_WRITE(last);
    col = run_end + 1;
  }
}

struct OccupancyGrid::RowPrefetcher final : ConeRowObserver {
  explicit RowPrefetcher(OccupancyGrid& g) : grid(g) {}
  void rowFound(const ConeRow& row) override { grid.prefetchConeRow(row); }
  OccupancyGrid& grid;
};

void OccupancyGrid::applyCell(int col, int row, float delta, float lo, float hi) {
  float* tile = findOrCreateTile(col >> kTileShift, row >> kTileShift);
  float& cell = tile[(row & kTileMask) * kTileSize + (col & kTileMask)];
  const bool unknown = std::isnan(cell);
  observed_cells_ += unknown ? 1u : 0u;
  cell = updatedCell(cell, unknown, delta, lo, hi);
  ++cell_updates_;
  noteTouched({col, row, col, row});
}

namespace {

// Validates the arguments of a cone update (misuse throws) and builds its geometry.
SonarCone checkedCone(const OccupancyGrid& grid, const Vec2& origin, double heading_rad,
                      double beam_width_rad, double range_m, bool echo,
                      const SonarInverseModel& model) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("OccupancyGrid::integrateSonar: " + what);
  };
  if (const auto error = sonarInverseModelError(model))
    fail("invalid model: " + *error);
  if (!std::isfinite(origin.x()) || !std::isfinite(origin.y()))
    fail("origin " + describe(origin) + " is not finite");
  if (!std::isfinite(heading_rad))
    fail("heading_rad is not finite");
  if (!(beam_width_rad > 0.0 && beam_width_rad < kPi))
    fail("beam_width_rad must be in (0, pi), got " + std::to_string(beam_width_rad));
  if (!std::isfinite(range_m) || range_m < 0.0)
    fail("range_m must be finite and >= 0, got " + std::to_string(range_m));
  const SonarCone cone = makeSonarCone(origin, heading_rad, beam_width_rad, range_m, echo, model);
  const double radius = cone.outerRadius();
  if (radius / grid.resolution_m() > OccupancyGrid::kMaxConeRadiusCells)
    fail("cone radius " + std::to_string(radius) + " m exceeds " +
         std::to_string(OccupancyGrid::kMaxConeRadiusCells) + " cells");
  if (!grid.isAddressable(origin, radius + 4.0 * grid.resolution_m()))
    fail("cone at " + describe(origin) + " reaches beyond the addressable cells");
  return cone;
}

}  // namespace

void OccupancyGrid::integrateSonar(const Vec2& origin, double heading_rad, double beam_width_rad,
                                   double range_m, bool echo, const SonarInverseModel& model) {
  const SonarCone cone =
      checkedCone(*this, origin, heading_rad, beam_width_rad, range_m, echo, model);
  // The cells of a cone are scattered over a cache line or two per row, and the grid (4 bytes a
  // cell) is larger than L2: each row is a cache miss the hardware prefetcher cannot foresee, so
  // the update was bound by memory latency. Each row's lines are requested as soon as the scan
  // finds the row, so that the fetches overlap the rest of the scan and one another. The tile
  // table therefore covers the cone's bounding box (a superset of the cells it touches).
  const CellRect bounds = coneCellBounds(cone, resolution_m_);
  cache_tx0_ = bounds.col0 >> kTileShift;
  cache_ty0_ = bounds.row0 >> kTileShift;
  cache_width_ = (bounds.col1 >> kTileShift) - cache_tx0_ + 1;
  const int cache_height = (bounds.row1 >> kTileShift) - cache_ty0_ + 1;
  tile_cache_.assign(
      static_cast<std::size_t>(cache_width_) * static_cast<std::size_t>(cache_height), nullptr);
  RowPrefetcher prefetcher(*this);
  scanConeRows(cone, resolution_m_, scratch_rows_, &prefetcher);
  if (scratch_rows_.empty())
    return;
  // Rows come ascending.
  CellRect touched{std::numeric_limits<int>::max(), scratch_rows_.front().row,
                   std::numeric_limits<int>::min(), scratch_rows_.back().row};
  ConeUpdater updater(static_cast<float>(model.free_log_odds),
                      static_cast<float>(model.occupied_log_odds),
                      static_cast<float>(model.clamp_min), static_cast<float>(model.clamp_max));
  for (const ConeRow& r : scratch_rows_) {
    touched.col0 = std::min(touched.col0, r.col0);
    touched.col1 = std::max(touched.col1, r.col1);
    applyConeRow(r, updater);
  }
  observed_cells_ += updater.fresh();
  noteTouched(touched);
}

void OccupancyGrid::integrateSonarNaive(const Vec2& origin, double heading_rad,
                                        double beam_width_rad, double range_m, bool echo,
                                        const SonarInverseModel& model) {
  const SonarCone cone =
      checkedCone(*this, origin, heading_rad, beam_width_rad, range_m, echo, model);
  const CellRect bounds = coneCellBounds(cone, resolution_m_);
  const auto lo = static_cast<float>(model.clamp_min);
  const auto hi = static_cast<float>(model.clamp_max);
  for (int row = bounds.row0; row <= bounds.row1; ++row) {
    for (int col = bounds.col0; col <= bounds.col1; ++col) {
      const ConeZone zone = cone.classifyCellWithAngles(col, row, resolution_m_);
      if (zone == ConeZone::kOutside)
        continue;
      const double delta = zone == ConeZone::kFree ? model.free_log_odds : model.occupied_log_odds;
      applyCell(col, row, static_cast<float>(delta), lo, hi);
    }
  }
}

Box2 OccupancyGrid::observedBounds() const {
  Box2 box;
  if (observed_rect_.empty())
    return box;
  box.extend(Vec2(observed_rect_.col0 * resolution_m_, observed_rect_.row0 * resolution_m_));
  box.extend(Vec2((observed_rect_.col1 + 1.0) * resolution_m_,
                  (observed_rect_.row1 + 1.0) * resolution_m_));
  return box;
}

double OccupancyGrid::exploredArea_m2() const {
  return static_cast<double>(observed_cells_) * resolution_m_ * resolution_m_;
}

OccupancyGrid::CellRect OccupancyGrid::takeDirtyRect() {
  return std::exchange(dirty_rect_, CellRect{});
}

void OccupancyGrid::copyLogOdds(const CellRect& rect, std::vector<float>& out) const {
  out.clear();
  if (rect.empty())
    return;
  const auto width = static_cast<std::size_t>(rect.width());
  out.assign(width * static_cast<std::size_t>(rect.height()), kUnobserved);
  for (int ty = rect.row0 >> kTileShift; ty <= rect.row1 >> kTileShift; ++ty) {
    const int r0 = std::max(rect.row0, ty * kTileSize);
    const int r1 = std::min(rect.row1, ty * kTileSize + kTileMask);
    for (int tx = rect.col0 >> kTileShift; tx <= rect.col1 >> kTileShift; ++tx) {
      const float* tile = findTile(tx, ty);
      if (tile == nullptr)
        continue;
      const int c0 = std::max(rect.col0, tx * kTileSize);
      const int c1 = std::min(rect.col1, tx * kTileSize + kTileMask);
      const auto n = static_cast<std::size_t>(c1 - c0 + 1);
      for (int r = r0; r <= r1; ++r) {
        const float* src = tile + (r & kTileMask) * kTileSize + (c0 & kTileMask);
        float* dst = out.data() + static_cast<std::size_t>(r - rect.row0) * width +
                     static_cast<std::size_t>(c0 - rect.col0);
        std::memcpy(dst, src, n * sizeof(float));
      }
    }
  }
}

RasterMap OccupancyGrid::toRaster() const {
  RasterMap map;
  map.resolution_m = resolution_m_;
  if (observed_rect_.empty())
    return map;
  map.width = observed_rect_.width();
  map.height = observed_rect_.height();
  map.origin = Pose2{observed_rect_.col0 * resolution_m_, observed_rect_.row0 * resolution_m_, 0.0};
  std::vector<float> log_odds;
  copyLogOdds(observed_rect_, log_odds);
  map.cells.resize(log_odds.size());
  std::transform(log_odds.begin(), log_odds.end(), map.cells.begin(), [](float l) {
    if (std::isnan(l))
      return RasterMap::kUnknown;
    const double p = 1.0 / (1.0 + std::exp(-static_cast<double>(l)));
    return static_cast<std::int8_t>(std::lround(100.0 * p));
  });
  return map;
}

std::size_t OccupancyGrid::memoryBytes() const {
  return tiles_.size() * (static_cast<std::size_t>(kTileCells) * sizeof(float)) +
         tile_index_.size() * (sizeof(TileKey) + sizeof(std::uint32_t) + 2 * sizeof(void*));
}

bool operator==(const OccupancyGrid& a, const OccupancyGrid& b) {
  if (a.resolution_m_ != b.resolution_m_ || a.observed_cells_ != b.observed_cells_ ||
      a.tile_index_.size() != b.tile_index_.size())
    return false;
  // Every allocated tile holds at least one observed cell (tiles are created by a write), so
  // equal grids have the same tile set.
  for (const auto& [key, index] : a.tile_index_) {
    const auto it = b.tile_index_.find(key);
    if (it == b.tile_index_.end())
      return false;
    if (std::memcmp(a.tiles_[index].data(), b.tiles_[it->second].data(),
                    static_cast<std::size_t>(OccupancyGrid::kTileCells) * sizeof(float)) != 0)
      return false;
  }
  return true;
}

}  // namespace irgs
