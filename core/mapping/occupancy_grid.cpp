#include "core/mapping/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// The AVX2 path is compiled on x86-64 with GCC or Clang (function-level target attributes) and
// used where the CPU has AVX2 (gridSimdSupported).
#if defined(__x86_64__) && defined(__GNUC__)
#define IRGS_GRID_AVX2 1
#include <immintrin.h>
#define IRGS_TARGET_AVX2 __attribute__((target("avx2")))
#define IRGS_TARGET_AVX512 __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl")))
#else
#define IRGS_GRID_AVX2 0
#endif

#include "core/mapping/sonar_cone.hpp"
#include "core/mapping/sonar_cone_scan.hpp"

// Storage (see docs/decisions/grid.md): 64x64-cell tiles of log-odds in 16-bit fixed point
// (steps of kLogOddsStep), allocated on the first write to any of their cells and found through a
// hash map on packed tile coordinates. -32768 marks a never-observed cell, so "observed" costs no
// extra memory and the update loop learns it from the value it loads anyway. A cone update first
// scans the cone into rows (each row: its cells and, within them, the free run;
// sonar_cone_scan.hpp, all rows at once, vectorised), then updates each row's cells: with SSE2 by
// runs of equal increments (RunUpdater), or with AVX2 / AVX-512 sixteen / thirty-two cells a step
// where the CPU has them (chosen at run time, the same bits). Tiles are found through a
// persistent direct-mapped cache in front of the hash map (tile_slots_). The row and tile buffers
// are kept between calls, so a warm update allocates nothing.

#if defined(__GNUC__)
#define IRGS_ALWAYS_INLINE __attribute__((always_inline))
#else
#define IRGS_ALWAYS_INLINE
#endif

namespace irgs {
namespace {

constexpr std::int16_t kUnobservedCell = std::numeric_limits<std::int16_t>::min();
constexpr float kUnobservedLogOdds = std::numeric_limits<float>::quiet_NaN();
constexpr auto kCellStep = static_cast<float>(OccupancyGrid::kLogOddsStep);  // exact: 2^-12
constexpr int kTileMask = OccupancyGrid::kTileSize - 1;

// A cell's log-odds, `unobserved` for a never-observed cell.
inline float cellLogOdds(std::int16_t v, float unobserved) {
  return v == kUnobservedCell ? unobserved : static_cast<float>(v) * kCellStep;
}

// The update of one cell: an unobserved cell starts from 0, then delta is added and the sum
// clamped to [lo, hi] (all in cell steps, -32767 <= lo <= hi <= 32767, |delta| <= 32767). Every
// path computes exactly this. The SIMD ones add with 16-bit saturation, then take the max with lo
// and the min with hi: saturation only moves a sum beyond +-32767 to -32768 or 32767, which the
// clamp takes to lo or hi as it would the exact sum.
inline std::int16_t updatedCell(std::int16_t v, int delta, int lo, int hi) {
  const int start = v == kUnobservedCell ? 0 : v;
  return static_cast<std::int16_t>(std::clamp(start + delta, lo, hi));
}

// Cone cells are updated by runs: a run is cells [a, b] of one tile row that all get the same
// increment (a row of a cone is at most three runs per tile: occupied, free, occupied). With SSE2
// (every x86-64) a run is whole aligned groups of eight cells, the first and last blended with a
// lane mask so that cells outside [a, b] are written back unchanged; elsewhere a plain loop. Both
// compute exactly updatedCell() for each cell. The count of cells that were unobserved is
// accumulated per 16-bit lane through a row (at most one cell in eight of a row's at most 2^16 + 1
// cells, plus one a tile: < 2^15) and per 32-bit lane over the cone (endRow), read once per cone.
#if defined(__SSE2__)
class RunUpdater {
 public:
  RunUpdater(int free_delta, int occupied_delta, int lo, int hi)
      : free_(_mm_set1_epi16(static_cast<std::int16_t>(free_delta))),
        occupied_(_mm_set1_epi16(static_cast<std::int16_t>(occupied_delta))),
        lo_(_mm_set1_epi16(static_cast<std::int16_t>(lo))),
        hi_(_mm_set1_epi16(static_cast<std::int16_t>(hi))) {}

  // Cells [a, b] of the tile row starting at `row` (0 <= a <= b < kTileSize). Groups start at
  // multiples of eight cells of the row, so they never leave it.
  IRGS_ALWAYS_INLINE void run(std::int16_t* row, int a, int b, bool free) {
    const __m128i delta = free ? free_ : occupied_;
    const int g0 = a & ~7;
    const int g1 = b & ~7;
    const __m128i head = _mm_cmpgt_epi16(iota(), _mm_set1_epi16(static_cast<short>((a & 7) - 1)));
    const __m128i tail = _mm_cmpgt_epi16(_mm_set1_epi16(static_cast<short>((b & 7) + 1)), iota());
    if (g0 == g1) {
      masked(row + g0, delta, _mm_and_si128(head, tail));
      return;
    }
    masked(row + g0, delta, head);
    for (int g = g0 + 8; g < g1; g += 8)
      full(row + g, delta);
    masked(row + g1, delta, tail);
  }

  // After each cone row: the row's 16-bit counts into the cone's 32-bit ones.
  IRGS_ALWAYS_INLINE void endRow() {
    fresh_ = _mm_add_epi32(fresh_, _mm_madd_epi16(row_fresh_, _mm_set1_epi16(1)));
    row_fresh_ = _mm_setzero_si128();
  }

  // Cells that were unobserved, over all rows so far (each 32-bit lane < 2^31 for any accepted
  // cone).
  std::uint64_t fresh() const {
    alignas(16) std::uint32_t lanes[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(lanes), fresh_);
    return std::uint64_t{lanes[0]} + lanes[1] + lanes[2] + lanes[3];
  }

 private:
  static __m128i iota() { return _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7); }
  // updatedCell() on eight lanes (see there for why saturation gives the same).
  IRGS_ALWAYS_INLINE __m128i updated(__m128i v, __m128i unknown, __m128i delta) const {
    const __m128i sum = _mm_adds_epi16(_mm_andnot_si128(unknown, v), delta);
    return _mm_min_epi16(hi_, _mm_max_epi16(lo_, sum));
  }
  IRGS_ALWAYS_INLINE __m128i unknownLanes(__m128i v) const {
    return _mm_cmpeq_epi16(v, _mm_set1_epi16(kUnobservedCell));
  }
  IRGS_ALWAYS_INLINE void full(std::int16_t* p, __m128i delta) {
    auto* const at = reinterpret_cast<__m128i*>(p);
    const __m128i v = _mm_loadu_si128(at);
    const __m128i unknown = unknownLanes(v);
    _mm_storeu_si128(at, updated(v, unknown, delta));
    row_fresh_ = _mm_sub_epi16(row_fresh_, unknown);  // a true lane is -1
  }
  IRGS_ALWAYS_INLINE void masked(std::int16_t* p, __m128i delta, __m128i mask) {
    auto* const at = reinterpret_cast<__m128i*>(p);
    const __m128i v = _mm_loadu_si128(at);
    const __m128i unknown = unknownLanes(v);
    const __m128i n = updated(v, unknown, delta);
    _mm_storeu_si128(at, _mm_or_si128(_mm_and_si128(mask, n), _mm_andnot_si128(mask, v)));
    row_fresh_ = _mm_sub_epi16(row_fresh_, _mm_and_si128(mask, unknown));
  }

  __m128i free_, occupied_, lo_, hi_;
  __m128i row_fresh_ = _mm_setzero_si128();
  __m128i fresh_ = _mm_setzero_si128();
};
#else
class RunUpdater {
 public:
  RunUpdater(int free_delta, int occupied_delta, int lo, int hi)
      : free_(free_delta), occupied_(occupied_delta), lo_(lo), hi_(hi) {}
  void run(std::int16_t* row, int a, int b, bool free) {
    const int delta = free ? free_ : occupied_;
    for (int i = a; i <= b; ++i) {
      fresh_ += row[i] == kUnobservedCell ? 1u : 0u;
      row[i] = updatedCell(row[i], delta, lo_, hi_);
    }
  }
  void endRow() {}
  std::uint64_t fresh() const { return fresh_; }

 private:
  int free_, occupied_, lo_, hi_;
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
  // !(|x| <= limit) is also true for NaN.
  const auto representable = [](double log_odds) {
    return std::abs(log_odds) <= OccupancyGrid::kMaxAbsLogOdds;
  };
  // Formatted only for an error: checkedCone asks on every cone.
  const auto within = [] {
    std::ostringstream text;
    text << std::fixed << std::setprecision(4) << "within +-" << OccupancyGrid::kMaxAbsLogOdds
         << " (the grid's 16-bit cells)";
    return text.str();
  };
  if (!representable(model.free_log_odds) || !representable(model.occupied_log_odds))
    return "free_log_odds and occupied_log_odds must be finite and " + within();
  if (!std::isfinite(model.arc_thickness_m) || model.arc_thickness_m < 0.0)
    return "arc_thickness_m must be finite and >= 0";
  if (!representable(model.clamp_min) || !representable(model.clamp_max) ||
      model.clamp_min > model.clamp_max)
    return "clamp_min and clamp_max must be finite, " + within() + ", with clamp_min <= clamp_max";
  if (std::isnan(model.no_echo_free_range_m) || model.no_echo_free_range_m < 0.0)
    return "no_echo_free_range_m must be >= 0";
  return std::nullopt;
}

bool gridSimdSupported(GridSimd simd) {
#if IRGS_GRID_AVX2
  // Needed when this runs before libgcc's own constructor (a grid built during static
  // initialisation); otherwise harmless.
  __builtin_cpu_init();
#endif
  switch (simd) {
    case GridSimd::kPortable:
      return true;
    case GridSimd::kAvx2:
#if IRGS_GRID_AVX2
      return __builtin_cpu_supports("avx2");
#else
      return false;
#endif
    case GridSimd::kAvx512:
#if IRGS_GRID_AVX2
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
#else
      return false;
#endif
  }
  return false;
}

GridSimd bestGridSimd() {
  static const GridSimd best = gridSimdSupported(GridSimd::kAvx512) ? GridSimd::kAvx512
                               : gridSimdSupported(GridSimd::kAvx2) ? GridSimd::kAvx2
                                                                    : GridSimd::kPortable;
  return best;
}

void OccupancyGrid::setSimd(GridSimd simd) {
  if (!gridSimdSupported(simd))
    throw std::invalid_argument("OccupancyGrid::setSimd: instruction set not supported here");
  simd_ = simd;
}

OccupancyGrid::OccupancyGrid(double resolution_m) : resolution_m_(resolution_m) {
  if (!std::isfinite(resolution_m) || !(resolution_m > 0.0))
    throw std::invalid_argument("OccupancyGrid: resolution_m must be finite and > 0, got " +
                                std::to_string(resolution_m));
}

OccupancyGrid::OccupancyGrid(const OccupancyGrid& other)
    : resolution_m_(other.resolution_m_),
      simd_(other.simd_),
      cell_updates_(other.cell_updates_),
      observed_cells_(other.observed_cells_),
      observed_rect_(other.observed_rect_),
      dirty_rect_(other.dirty_rect_),
      tiles_(other.tiles_),
      tile_index_(other.tile_index_) {}

OccupancyGrid& OccupancyGrid::operator=(const OccupancyGrid& other) {
  if (this != &other) {
    resolution_m_ = other.resolution_m_;
    simd_ = other.simd_;
    cell_updates_ = other.cell_updates_;
    observed_cells_ = other.observed_cells_;
    observed_rect_ = other.observed_rect_;
    dirty_rect_ = other.dirty_rect_;
    tiles_ = other.tiles_;
    tile_index_ = other.tile_index_;
    tile_slots_.clear();  // they point into the old tiles (reused buffers, other tiles)
  }
  return *this;
}

OccupancyGrid::~OccupancyGrid() = default;

OccupancyGrid::OccupancyGrid(OccupancyGrid&& other) noexcept
    : resolution_m_(other.resolution_m_),
      simd_(other.simd_),
      cell_updates_(std::exchange(other.cell_updates_, 0)),
      observed_cells_(std::exchange(other.observed_cells_, 0)),
      observed_rect_(std::exchange(other.observed_rect_, CellRect{})),
      dirty_rect_(std::exchange(other.dirty_rect_, CellRect{})),
      tiles_(std::move(other.tiles_)),
      tile_index_(std::move(other.tile_index_)) {
  other.tiles_.clear();
  other.tile_index_.clear();
  other.tile_slots_.clear();
}

OccupancyGrid& OccupancyGrid::operator=(OccupancyGrid&& other) noexcept {
  if (this != &other) {
    resolution_m_ = other.resolution_m_;
    simd_ = other.simd_;
    cell_updates_ = std::exchange(other.cell_updates_, 0);
    observed_cells_ = std::exchange(other.observed_cells_, 0);
    observed_rect_ = std::exchange(other.observed_rect_, CellRect{});
    dirty_rect_ = std::exchange(other.dirty_rect_, CellRect{});
    tiles_ = std::move(other.tiles_);
    tile_index_ = std::move(other.tile_index_);
    other.tiles_.clear();
    other.tile_index_.clear();
    tile_slots_.clear();
    other.tile_slots_.clear();
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

IRGS_ALWAYS_INLINE inline OccupancyGrid::TileKey OccupancyGrid::tileKey(int tx, int ty) {
  return (static_cast<TileKey>(static_cast<std::uint32_t>(tx)) << 32) |
         static_cast<TileKey>(static_cast<std::uint32_t>(ty));
}

const std::int16_t* OccupancyGrid::findTile(int tx, int ty) const {
  const auto it = tile_index_.find(tileKey(tx, ty));
  return it == tile_index_.end() ? nullptr : tiles_[it->second].data();
}

std::int16_t* OccupancyGrid::findOrCreateTile(int tx, int ty) {
  const auto [it, inserted] =
      tile_index_.try_emplace(tileKey(tx, ty), static_cast<std::uint32_t>(tiles_.size()));
  if (inserted)
    tiles_.emplace_back(static_cast<std::size_t>(kTileCells), kUnobservedCell);
  return tiles_[it->second].data();
}

OccupancyGrid::CellModel OccupancyGrid::cellModel(const SonarInverseModel& model) {
  // Rounded away from zero, so that a cell after one update is at least as far from 0 as the
  // increment: a threshold equal to an increment (grid_compare's -0.4 and the default free
  // increment) then classifies a cell with one update as the model means it. sonarInverseModelError
  // keeps every value within +-kMaxAbsLogOdds: +-32767 steps.
  // (Ceiling by truncation: std::ceil is a libm call without SSE4.1, 2 % of a 0.5 m cone.)
  const auto steps = [](double log_odds) {
    const double scaled = std::abs(log_odds) * (1.0 / kLogOddsStep);  // exact: a power of 2
    auto magnitude = static_cast<int>(scaled);
    magnitude += magnitude < scaled ? 1 : 0;
    return static_cast<CellValue>(log_odds < 0.0 ? -magnitude : magnitude);
  };
  return {steps(model.free_log_odds), steps(model.occupied_log_odds), steps(model.clamp_min),
          steps(model.clamp_max)};
}

float OccupancyGrid::logOdds(const Cell& c) const {
  const std::int16_t* tile = findTile(c.col >> kTileShift, c.row >> kTileShift);
  if (tile == nullptr)
    return 0.0f;
  const std::int16_t v = tile[(c.row & kTileMask) * kTileSize + (c.col & kTileMask)];
  return cellLogOdds(v, 0.0f);
}

double OccupancyGrid::probability(const Cell& c) const {
  // p = 1 / (1 + exp(-l)): the inverse of l = log(p / (1 - p)).
  return 1.0 / (1.0 + std::exp(-static_cast<double>(logOdds(c))));
}

bool OccupancyGrid::observed(const Cell& c) const {
  const std::int16_t* tile = findTile(c.col >> kTileShift, c.row >> kTileShift);
  return tile != nullptr &&
         tile[(c.row & kTileMask) * kTileSize + (c.col & kTileMask)] != kUnobservedCell;
}

IRGS_ALWAYS_INLINE inline std::size_t OccupancyGrid::slotIndex(int tx, int ty) {
  return static_cast<std::size_t>(((ty & kTileSlotMask) << kTileSlotShift) | (tx & kTileSlotMask));
}

IRGS_ALWAYS_INLINE inline std::int16_t* OccupancyGrid::slotTile(int tx, int ty) {
  const TileSlot& slot = tile_slots_[slotIndex(tx, ty)];
  if (slot.key == tileKey(tx, ty)) [[likely]]
    return slot.tile;
  return fillTileSlot(tx, ty);
}

std::int16_t* OccupancyGrid::fillTileSlot(int tx, int ty) {
  TileSlot& slot = tile_slots_[slotIndex(tx, ty)];
  slot.tile = findOrCreateTile(tx, ty);
  slot.key = tileKey(tx, ty);
  return slot.tile;
}

bool OccupancyGrid::coneTilesInSlots(const CellRect& cells) const {
  bool all = true;
  for (int ty = cells.row0 >> kTileShift; ty <= cells.row1 >> kTileShift; ++ty)
    for (int tx = cells.col0 >> kTileShift; tx <= cells.col1 >> kTileShift; ++tx)
      all &= tile_slots_[slotIndex(tx, ty)].key == tileKey(tx, ty);
  return all;
}

namespace {

// Prefetches (read, into L2) `lines` cache lines (1 or 2: a tile row is two) from `first` in
// each of `rows` consecutive rows of a tile. One loop per line count, so that the loop is the
// same for every row: a loop over the lines inside the loop over the rows was ~0.05 us slower a
// 0.5 m cone (with float cells).
void prefetchTileRows(const std::int16_t* first, int rows, int lines) {
  const std::int16_t* const end =
      first + static_cast<std::ptrdiff_t>(rows) * OccupancyGrid::kTileSize;
  constexpr int kStep = OccupancyGrid::kTileSize;
  constexpr int kLineCells = 64 / sizeof(std::int16_t);
  if (lines == 1) {
    for (const std::int16_t* p = first; p != end; p += kStep)
      __builtin_prefetch(p, 0, 2);
    return;
  }
  for (const std::int16_t* p = first; p != end; p += kStep) {
    __builtin_prefetch(p, 0, 2);
    __builtin_prefetch(p + kLineCells, 0, 2);
  }
}

}  // namespace

void OccupancyGrid::prefetchConeBox(const ConeScanSetup& s) const {
  if (!s.has_cells)
    return;
  const long lines_per_row = (s.hi >> 5) - (s.lo >> 5) + 1;  // 32 cells a line
  if (lines_per_row * (s.row1 - s.row0 + 1) > kMaxPrefetchLines)
    return;
  for (int ty = s.row0 >> kTileShift; ty <= s.row1 >> kTileShift; ++ty) {
    const int r0 = std::max(s.row0, ty << kTileShift) & kTileMask;
    const int r1 = std::min(s.row1, (ty << kTileShift) + kTileMask) & kTileMask;
    for (int tx = s.lo >> kTileShift; tx <= s.hi >> kTileShift; ++tx) {
      // Tiles not yet in their slot are skipped: creating them here would allocate tiles the
      // cone may not touch, and a new tile is in cache anyway.
      const TileSlot& slot = tile_slots_[slotIndex(tx, ty)];
      if (slot.key != tileKey(tx, ty))
        continue;
      const int c0 = std::max(s.lo, tx << kTileShift) & kTileMask & ~31;
      const int c1 = std::min(s.hi, (tx << kTileShift) + kTileMask) & kTileMask;
      prefetchTileRows(slot.tile + r0 * kTileSize + c0, r1 - r0 + 1, ((c1 - c0) >> 5) + 1);
    }
  }
}

namespace {

// into.extend(cells) for a non-empty `cells`, one test instead of CellRect::extend's three.
IRGS_ALWAYS_INLINE inline void unite(OccupancyGrid::CellRect& into,
                                     const OccupancyGrid::CellRect& cells) {
  if (into.empty()) {
    into = cells;
    return;
  }
  into.col0 = std::min(into.col0, cells.col0);
  into.row0 = std::min(into.row0, cells.row0);
  into.col1 = std::max(into.col1, cells.col1);
  into.row1 = std::max(into.row1, cells.row1);
}

}  // namespace

void OccupancyGrid::noteTouched(const CellRect& cells) {
  if (cells.empty())
    return;
  unite(observed_rect_, cells);
  unite(dirty_rect_, cells);
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
    std::int16_t* cells = slotTile(tx, ty) + row_offset;
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
  u.endRow();
  cell_updates_ += static_cast<std::uint64_t>(r.col1 - r.col0 + 1);
}

void OccupancyGrid::applyCell(int col, int row, int delta, int lo, int hi) {
  std::int16_t* tile = findOrCreateTile(col >> kTileShift, row >> kTileShift);
  std::int16_t& cell = tile[(row & kTileMask) * kTileSize + (col & kTileMask)];
  observed_cells_ += cell == kUnobservedCell ? 1u : 0u;
  cell = updatedCell(cell, delta, lo, hi);
  ++cell_updates_;
  noteTouched({col, row, col, row});
}

namespace {

// Row i of `rows` as final cells (the exact scan when the estimates left it undecided); returns
// its first cell, > col1[i] when it has none.
IRGS_ALWAYS_INLINE inline int finalRow(const SonarCone& cone, const ConeScanSetup& setup,
                                       ConeRowEstimates& rows, int i) {
  if (rows.undecided(i)) [[unlikely]] {
    ConeRow r;
    if (coneRowAt(cone, setup, rows, i, r))
      rows.set(i, r.col0, r.col1, r.free0, r.free1);
    else
      rows.set(i, 0, -1, 0, -1);
  }
  return rows.c0(i);
}

// Runs the exact scan on the rows the estimates left undecided (rare), before the update loop:
// that loop then reads every row as final cells, and calls nothing out of line for it. The AVX
// paths call it only when anyUndecidedAvx2 / anyUndecidedAvx512 finds such a row.
void resolveUndecidedRows(const SonarCone& cone, const ConeScanSetup& setup,
                          ConeRowEstimates& rows) {
  for (int i = 0; i < rows.count; ++i)
    finalRow(cone, setup, rows, i);
}

// The rectangle of a cone's non-empty rows and their number of cells (the AVX paths, from a
// vectorised pass over the rows: touchedRowsAvx2, touchedRowsAvx512).
struct ConeRowsTouched {
  OccupancyGrid::CellRect rect;
  std::uint64_t cells = 0;

  // From per-lane minima of the first columns, maxima of the last ones and cell counts (exact
  // integers as doubles), rows first to last.
  static ConeRowsTouched fromLanes(const double* least, const double* most, const double* cells,
                                   int lanes, int first, int last) {
    double col0 = least[0], col1 = most[0], n = cells[0];
    for (int k = 1; k < lanes; ++k) {
      col0 = std::min(col0, least[k]);
      col1 = std::max(col1, most[k]);
      n += cells[k];
    }
    return {{static_cast<int>(col0), first, static_cast<int>(col1), last},
            static_cast<std::uint64_t>(n)};
  }
};

// Extends the cone's touched rectangle by a non-empty row (rows come ascending).
IRGS_ALWAYS_INLINE inline void touchRow(OccupancyGrid::CellRect& touched, int c0, int c1, int row) {
  if (touched.empty()) {
    touched = {c0, row, c1, row};
    return;
  }
  touched.col0 = std::min(touched.col0, c0);
  touched.col1 = std::max(touched.col1, c1);
  touched.row1 = row;
}

}  // namespace

#if IRGS_GRID_AVX2
namespace {

// A free run's bounds relative to a tile row, clamped to [-1, kTileSize] so that they fit in 16
// bits: the same cells of [0, kTileSize) are within them.
IRGS_ALWAYS_INLINE inline std::int16_t tileBound(int at) {
  return static_cast<std::int16_t>(std::clamp(at, -1, OccupancyGrid::kTileSize));
}

// The update of cells [a, b] of one tile row (0 <= a <= b < kTileSize), [f0, f1] of them free
// (none when f0 > f1), sixteen at a time: every group of sixteen aligned within the row that
// meets [a, b] is loaded, updated per lane with the free or occupied increment, and stored with
// the lanes outside [a, b] unchanged. The per-lane operations are RunUpdater's (updatedCell(),
// bit for bit), so the result does not depend on the path.
struct Avx2Cells {
  __m256i free_delta, occupied_delta, lo, hi, unobserved;
  __m256i iota;  // 0, 1, ..., 15
  // Per 16-bit lane, this row's cells that were unobserved (at most four a tile: < 2^15 for any
  // row); per 32-bit lane, the cone's (endRow).
  __m256i row_fresh, fresh;

  IRGS_TARGET_AVX2 IRGS_ALWAYS_INLINE void piece(std::int16_t* row, int a, int b, int f0, int f1) {
    const __m256i before_a = _mm256_set1_epi16(static_cast<short>(a - 1));
    const __m256i after_b = _mm256_set1_epi16(static_cast<short>(b + 1));
    const __m256i before_f = _mm256_set1_epi16(static_cast<short>(tileBound(f0) - 1));
    const __m256i after_f = _mm256_set1_epi16(static_cast<short>(tileBound(f1) + 1));
    for (int g = a & ~15; g <= b; g += 16) {
      const __m256i idx = _mm256_add_epi16(_mm256_set1_epi16(static_cast<short>(g)), iota);
      const __m256i in =
          _mm256_and_si256(_mm256_cmpgt_epi16(idx, before_a), _mm256_cmpgt_epi16(after_b, idx));
      const __m256i free =
          _mm256_and_si256(_mm256_cmpgt_epi16(idx, before_f), _mm256_cmpgt_epi16(after_f, idx));
      const __m256i delta = _mm256_blendv_epi8(occupied_delta, free_delta, free);
      auto* const at = reinterpret_cast<__m256i*>(row + g);
      const __m256i v = _mm256_loadu_si256(at);
      const __m256i unknown = _mm256_cmpeq_epi16(v, unobserved);
      const __m256i sum = _mm256_adds_epi16(_mm256_andnot_si256(unknown, v), delta);
      const __m256i n = _mm256_min_epi16(hi, _mm256_max_epi16(lo, sum));
      _mm256_storeu_si256(at, _mm256_blendv_epi8(v, n, in));
      row_fresh = _mm256_sub_epi16(row_fresh, _mm256_and_si256(unknown, in));  // true is -1
    }
  }

  IRGS_TARGET_AVX2 IRGS_ALWAYS_INLINE void endRow() {
    fresh = _mm256_add_epi32(fresh, _mm256_madd_epi16(row_fresh, _mm256_set1_epi16(1)));
    row_fresh = _mm256_setzero_si256();
  }
};

// Whether the estimates left a row undecided (16 of the bench's 4096 0.5 m cones have one), four
// rows a compare: testing each row in resolveUndecidedRows' scalar loop cost ~2 % of a 0.5 m
// cone's time.
IRGS_TARGET_AVX2 IRGS_ALWAYS_INLINE inline bool anyUndecidedAvx2(const ConeRowEstimates& rows) {
  const __m256d undecided = _mm256_set1_pd(kUndecidedRow);
  __m256d found = _mm256_setzero_pd();
  int i = 0;
  for (; i + 4 <= rows.count; i += 4)
    found =
        _mm256_or_pd(found, _mm256_cmp_pd(_mm256_loadu_pd(rows.col0 + i), undecided, _CMP_EQ_OQ));
  bool any = _mm256_movemask_pd(found) != 0;
  for (; i < rows.count; ++i)
    any |= rows.undecided(i);
  return any;
}

// touchedRowsAvx512 four rows a step.
struct Avx2RowsTouched {
  __m256d least, most, cells;  // per lane: the least first column, the most last one, cells
  int first = -1, last = -1;

  // Rows at, ..., at + 3, cells [c0, c1] each (none when c0 > c1).
  IRGS_TARGET_AVX2 IRGS_ALWAYS_INLINE void add(__m256d c0, __m256d c1, int at) {
    const __m256d used = _mm256_cmp_pd(c0, c1, _CMP_LE_OQ);
    const auto bits = static_cast<unsigned>(_mm256_movemask_pd(used));
    if (bits == 0)
      return;
    first = first < 0 ? at + __builtin_ctz(bits) : first;
    last = at + 31 - __builtin_clz(bits);
    least = _mm256_blendv_pd(least, _mm256_min_pd(c0, least), used);
    most = _mm256_blendv_pd(most, _mm256_max_pd(c1, most), used);
    const __m256d width = _mm256_add_pd(_mm256_sub_pd(c1, c0), _mm256_set1_pd(1.0));
    cells = _mm256_add_pd(cells, _mm256_and_pd(used, width));
  }
};

IRGS_TARGET_AVX2 IRGS_ALWAYS_INLINE inline ConeRowsTouched touchedRowsAvx2(
    const ConeRowEstimates& rows, int row0) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Avx2RowsTouched t{_mm256_set1_pd(kInf), _mm256_set1_pd(-kInf), _mm256_setzero_pd()};
  int i = 0;
  for (; i + 4 <= rows.count; i += 4)
    t.add(_mm256_loadu_pd(rows.col0 + i), _mm256_loadu_pd(rows.col1 + i), i);
  if (i < rows.count) {
    alignas(32) double c0[4] = {0.0, 0.0, 0.0, 0.0}, c1[4] = {-1.0, -1.0, -1.0, -1.0};
    for (int k = 0; i + k < rows.count; ++k) {
      c0[k] = rows.col0[i + k];
      c1[k] = rows.col1[i + k];
    }
    t.add(_mm256_load_pd(c0), _mm256_load_pd(c1), i);
  }
  if (t.first < 0)
    return {};
  alignas(32) double lanes_least[4], lanes_most[4], lanes_cells[4];
  _mm256_store_pd(lanes_least, t.least);
  _mm256_store_pd(lanes_most, t.most);
  _mm256_store_pd(lanes_cells, t.cells);
  return ConeRowsTouched::fromLanes(lanes_least, lanes_most, lanes_cells, 4, row0 + t.first,
                                    row0 + t.last);
}

}  // namespace

IRGS_TARGET_AVX2 std::uint64_t OccupancyGrid::applyConeRowsAvx2(const SonarCone& cone,
                                                                const ConeScanSetup& setup,
                                                                ConeRowEstimates& rows,
                                                                CellRect& touched,
                                                                CellModel model) {
  Avx2Cells u{_mm256_set1_epi16(model.free_delta),
              _mm256_set1_epi16(model.occupied_delta),
              _mm256_set1_epi16(model.lo),
              _mm256_set1_epi16(model.hi),
              _mm256_set1_epi16(kUnobservedCell),
              _mm256_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15),
              _mm256_setzero_si256(),
              _mm256_setzero_si256()};
  if (anyUndecidedAvx2(rows)) [[unlikely]]
    resolveUndecidedRows(cone, setup, rows);
  const ConeRowsTouched rows_touched = touchedRowsAvx2(rows, setup.row0);
  // The row arrays, bounds and tile slots in locals: the compiler cannot tell that the tile
  // stores leave them alone, and would reload them every row.
  const int count = rows.count, row0 = setup.row0;
  const double* const col0 = rows.col0;
  const double* const col1 = rows.col1;
  const double* const free0 = rows.free0;
  const double* const free1 = rows.free1;
  const TileSlot* const slots = tile_slots_.data();
  const auto update = [&](auto tile_of) IRGS_TARGET_AVX2 IRGS_ALWAYS_INLINE {
    for (int i = 0; i < count; ++i) {
      const int c0 = static_cast<int>(col0[i]), c1 = static_cast<int>(col1[i]);
      if (c0 > c1)
        continue;
      const int row = row0 + i;
      const int f0 = static_cast<int>(free0[i]), f1 = static_cast<int>(free1[i]);
      const int ty = row >> kTileShift;
      const int row_offset = (row & kTileMask) * kTileSize;
      for (int col = c0; col <= c1;) {
        const int tx = col >> kTileShift;
        const int base = tx * kTileSize;
        const int run_end = std::min(c1, base + kTileMask);
        u.piece(tile_of(tx, ty) + row_offset, col - base, run_end - base, f0 - base, f1 - base);
        col = run_end + 1;
      }
      u.endRow();
    }
  };
  if (coneTilesInSlots(rows_touched.rect))
    update([slots](int tx, int ty) { return slots[slotIndex(tx, ty)].tile; });
  else
    update([this](int tx, int ty) { return slotTile(tx, ty); });
  touched = rows_touched.rect;
  cell_updates_ += rows_touched.cells;
  alignas(32) std::uint32_t lanes[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), u.fresh);
  std::uint64_t fresh = 0;
  for (const std::uint32_t n : lanes)
    fresh += n;
  return fresh;
}

namespace {

// Avx2Cells with thirty-two lanes and mask registers: cells outside [a, b] are neither loaded
// nor stored.
struct Avx512Cells {
  __m512i free_delta, occupied_delta, lo, hi, unobserved;
  __m512i iota;  // 0, 1, ..., 31
  // Per 16-bit lane, this row's cells that were unobserved (at most two a tile: < 2^15 for any
  // row), counted with one masked subtraction a group (a popcount of the mask into a scalar sum
  // took more instructions, and the update is bound by instruction count on the rows of small
  // cones); per 32-bit lane, the cone's (endRow).
  __m512i row_fresh = _mm512_setzero_si512();
  __m512i fresh = _mm512_setzero_si512();

  IRGS_TARGET_AVX512 IRGS_ALWAYS_INLINE void piece(std::int16_t* row, int a, int b, int f0,
                                                   int f1) {
    // Locals, so that the loop keeps them in registers.
    const __m512i free_d = free_delta, occupied_d = occupied_delta;
    const __m512i low = lo, high = hi, none = unobserved;
    const __m512i thirty_two = _mm512_set1_epi16(32), minus_one = _mm512_set1_epi16(-1);
    __m512i counts = row_fresh;
    const __m512i va = _mm512_set1_epi16(static_cast<short>(a));
    const __m512i vb = _mm512_set1_epi16(static_cast<short>(b));
    const __m512i vf0 = _mm512_set1_epi16(tileBound(f0));
    const __m512i vf1 = _mm512_set1_epi16(tileBound(f1));
    const int g0 = a & ~31;
    // The lanes' cell indices, stepped with the pointer (not rebuilt from the group start).
    __m512i idx = _mm512_add_epi16(_mm512_set1_epi16(static_cast<short>(g0)), iota);
    const std::int16_t* const last = row + b;
    for (std::int16_t* p = row + g0; p <= last; p += 32, idx = _mm512_add_epi16(idx, thirty_two)) {
      const __mmask32 in = _mm512_mask_cmple_epi16_mask(_mm512_cmpge_epi16_mask(idx, va), idx, vb);
      const __mmask32 free =
          _mm512_mask_cmple_epi16_mask(_mm512_mask_cmpge_epi16_mask(in, idx, vf0), idx, vf1);
      const __m512i delta = _mm512_mask_blend_epi16(free, occupied_d, free_d);
      const __m512i v = _mm512_maskz_loadu_epi16(in, p);
      const __mmask32 unknown = _mm512_mask_cmpeq_epi16_mask(in, v, none);
      // Unobserved lanes keep delta: 0 + delta.
      const __m512i sum = _mm512_mask_adds_epi16(delta, _knot_mask32(unknown), v, delta);
      const __m512i n = _mm512_min_epi16(high, _mm512_max_epi16(low, sum));
      _mm512_mask_storeu_epi16(p, in, n);
      counts = _mm512_mask_sub_epi16(counts, unknown, counts, minus_one);  // +1 where unknown
    }
    row_fresh = counts;
  }

  IRGS_TARGET_AVX512 IRGS_ALWAYS_INLINE void endRow() {
    fresh = _mm512_add_epi32(fresh, _mm512_madd_epi16(row_fresh, _mm512_set1_epi16(1)));
    row_fresh = _mm512_setzero_si512();
  }

  // (Summed through memory: GCC 12 warns inside _mm512_reduce_add_epi32, -Wuninitialized.)
  IRGS_TARGET_AVX512 std::uint64_t freshCount() const {
    alignas(64) std::uint32_t lanes[16];
    _mm512_store_si512(lanes, fresh);
    std::uint64_t sum = 0;
    for (const std::uint32_t n : lanes)
      sum += n;
    return sum;
  }
};

// anyUndecidedAvx2 eight rows a compare, the last ones masked.
IRGS_TARGET_AVX512 IRGS_ALWAYS_INLINE inline bool anyUndecidedAvx512(const ConeRowEstimates& rows) {
  const __m512d undecided = _mm512_set1_pd(kUndecidedRow);
  __mmask8 found = 0;
  int i = 0;
  for (; i + 8 <= rows.count; i += 8)
    found |= _mm512_cmpeq_pd_mask(_mm512_loadu_pd(rows.col0 + i), undecided);
  const auto tail = static_cast<__mmask8>((1u << (rows.count - i)) - 1u);  // rows.count - i < 8
  found |= _mm512_mask_cmpeq_pd_mask(tail, _mm512_maskz_loadu_pd(tail, rows.col0 + i), undecided);
  return found != 0;
}

// The rectangle of a cone's non-empty rows and their cell count, eight rows a step before the
// update loop: accumulated in that loop, the four bounds and the count took registers that the
// loop's other values then lost to the stack (with the AVX2 version: 290 fewer instructions a
// 0.5 m cone under callgrind).
IRGS_TARGET_AVX512 IRGS_ALWAYS_INLINE inline ConeRowsTouched touchedRowsAvx512(
    const ConeRowEstimates& rows, int row0) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  __m512d least = _mm512_set1_pd(kInf), most = _mm512_set1_pd(-kInf);
  __m512d cells = _mm512_setzero_pd();
  const __m512d one = _mm512_set1_pd(1.0);
  int first = -1, last = -1;
  for (int i = 0; i < rows.count; i += 8) {
    const int left = rows.count - i;
    const auto valid = static_cast<__mmask8>(left >= 8 ? 0xffu : (1u << left) - 1u);
    const __m512d c0 = _mm512_maskz_loadu_pd(valid, rows.col0 + i);
    const __m512d c1 = _mm512_maskz_loadu_pd(valid, rows.col1 + i);
    const __mmask8 used = _mm512_mask_cmp_pd_mask(valid, c0, c1, _CMP_LE_OQ);
    least = _mm512_mask_min_pd(least, used, least, c0);
    most = _mm512_mask_max_pd(most, used, most, c1);
    cells = _mm512_mask_add_pd(cells, used, cells, _mm512_add_pd(_mm512_sub_pd(c1, c0), one));
    if (used != 0) {
      first = first < 0 ? i + __builtin_ctz(used) : first;
      last = i + 31 - __builtin_clz(used);
    }
  }
  if (first < 0)
    return {};
  alignas(64) double lanes_least[8], lanes_most[8], lanes_cells[8];
  _mm512_store_pd(lanes_least, least);
  _mm512_store_pd(lanes_most, most);
  _mm512_store_pd(lanes_cells, cells);
  return ConeRowsTouched::fromLanes(lanes_least, lanes_most, lanes_cells, 8, row0 + first,
                                    row0 + last);
}

}  // namespace

IRGS_TARGET_AVX512 std::uint64_t OccupancyGrid::applyConeRowsAvx512(const SonarCone& cone,
                                                                    const ConeScanSetup& setup,
                                                                    ConeRowEstimates& rows,
                                                                    CellRect& touched,
                                                                    CellModel model) {
  alignas(64) static constexpr std::int16_t kIota[32] = {0,  1,  2,  3,  4,  5,  6,  7,  8,  9,  10,
                                                         11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21,
                                                         22, 23, 24, 25, 26, 27, 28, 29, 30, 31};
  Avx512Cells u{_mm512_set1_epi16(model.free_delta), _mm512_set1_epi16(model.occupied_delta),
                _mm512_set1_epi16(model.lo),         _mm512_set1_epi16(model.hi),
                _mm512_set1_epi16(kUnobservedCell),  _mm512_load_si512(kIota)};
  if (anyUndecidedAvx512(rows)) [[unlikely]]
    resolveUndecidedRows(cone, setup, rows);
  const ConeRowsTouched rows_touched = touchedRowsAvx512(rows, setup.row0);
  // The row arrays, bounds and tile slots in locals: the compiler cannot tell that the tile
  // stores leave them alone, and would reload them every row.
  const int count = rows.count, row0 = setup.row0;
  const double* const col0 = rows.col0;
  const double* const col1 = rows.col1;
  const double* const free0 = rows.free0;
  const double* const free1 = rows.free1;
  const TileSlot* const slots = tile_slots_.data();
  const auto update = [&](auto tile_of) IRGS_TARGET_AVX512 IRGS_ALWAYS_INLINE {
    for (int i = 0; i < count; ++i) {
      const int c0 = static_cast<int>(col0[i]), c1 = static_cast<int>(col1[i]);
      if (c0 > c1)
        continue;
      const int row = row0 + i;
      const int f0 = static_cast<int>(free0[i]), f1 = static_cast<int>(free1[i]);
      const int ty = row >> kTileShift;
      const int row_offset = (row & kTileMask) * kTileSize;
      for (int col = c0; col <= c1;) {
        const int tx = col >> kTileShift;
        const int base = tx * kTileSize;
        const int run_end = std::min(c1, base + kTileMask);
        u.piece(tile_of(tx, ty) + row_offset, col - base, run_end - base, f0 - base, f1 - base);
        col = run_end + 1;
      }
      u.endRow();
    }
  };
  if (coneTilesInSlots(rows_touched.rect))
    update([slots](int tx, int ty) { return slots[slotIndex(tx, ty)].tile; });
  else
    update([this](int tx, int ty) { return slotTile(tx, ty); });
  touched = rows_touched.rect;
  cell_updates_ += rows_touched.cells;
  return u.freshCount();
}
#endif

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
  const ConeScanSetup setup =
      makeConeScanSetup(cone, resolution_m_, coneCellBounds(cone, resolution_m_));
  if (tile_slots_.empty())
    tile_slots_.assign(static_cast<std::size_t>(kTileSlots), TileSlot{});
  prefetchConeBox(setup);
  ConeRowEstimates rows;
  estimateConeRows(setup, scan_scratch_, rows, simd_);
  // Rows the estimates left undecided are scanned exactly: all first on the AVX paths, on the
  // way on the portable one. The box prefetch above is issued before the estimates so that the
  // lines arrive while they are computed (0.5 m cones: 15-25 % faster on a shared machine, no
  // measurable cost when the rows are in cache already). Prefetching each row's first and last
  // line as the rows are found, in an older version, lost to the hardware prefetchers (7-15 %);
  // so did prefetching the found rows' lines after the estimates.
  CellRect touched;
  const CellModel cells = cellModel(model);
#if IRGS_GRID_AVX2
  if (simd_ == GridSimd::kAvx512 || simd_ == GridSimd::kAvx2) {
    const std::uint64_t fresh = simd_ == GridSimd::kAvx512
                                    ? applyConeRowsAvx512(cone, setup, rows, touched, cells)
                                    : applyConeRowsAvx2(cone, setup, rows, touched, cells);
    observed_cells_ += fresh;
    noteTouched(touched);
    return;
  }
#endif
  ConeUpdater updater(cells.free_delta, cells.occupied_delta, cells.lo, cells.hi);
  ConeRow r;
  for (int i = 0; i < rows.count; ++i) {
    const int c0 = finalRow(cone, setup, rows, i), c1 = rows.c1(i);
    if (c0 > c1)
      continue;
    r = {setup.row0 + i, c0, c1, rows.f0(i), rows.f1(i)};
    touchRow(touched, c0, c1, r.row);
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
  const CellModel cells = cellModel(model);
  for (int row = bounds.row0; row <= bounds.row1; ++row) {
    for (int col = bounds.col0; col <= bounds.col1; ++col) {
      const ConeZone zone = cone.classifyCellWithAngles(col, row, resolution_m_);
      if (zone == ConeZone::kOutside)
        continue;
      applyCell(col, row, zone == ConeZone::kFree ? cells.free_delta : cells.occupied_delta,
                cells.lo, cells.hi);
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
  out.assign(width * static_cast<std::size_t>(rect.height()), kUnobservedLogOdds);
  for (int ty = rect.row0 >> kTileShift; ty <= rect.row1 >> kTileShift; ++ty) {
    const int r0 = std::max(rect.row0, ty * kTileSize);
    const int r1 = std::min(rect.row1, ty * kTileSize + kTileMask);
    for (int tx = rect.col0 >> kTileShift; tx <= rect.col1 >> kTileShift; ++tx) {
      const std::int16_t* tile = findTile(tx, ty);
      if (tile == nullptr)
        continue;
      const int c0 = std::max(rect.col0, tx * kTileSize);
      const int c1 = std::min(rect.col1, tx * kTileSize + kTileMask);
      const int n = c1 - c0 + 1;
      for (int r = r0; r <= r1; ++r) {
        const std::int16_t* src = tile + (r & kTileMask) * kTileSize + (c0 & kTileMask);
        float* dst = out.data() + static_cast<std::size_t>(r - rect.row0) * width +
                     static_cast<std::size_t>(c0 - rect.col0);
        for (int i = 0; i < n; ++i)
          dst[i] = cellLogOdds(src[i], kUnobservedLogOdds);
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
  return tiles_.size() * (static_cast<std::size_t>(kTileCells) * sizeof(CellValue)) +
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
                    static_cast<std::size_t>(OccupancyGrid::kTileCells) *
                        sizeof(OccupancyGrid::CellValue)) != 0)
      return false;
  }
  return true;
}

}  // namespace irgs
