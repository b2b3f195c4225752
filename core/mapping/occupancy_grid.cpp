#include "core/mapping/occupancy_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/mapping/sonar_cone.hpp"

// Storage (see docs/decisions/grid.md): 64x64-cell tiles of float log-odds, allocated on the
// first write to any of their cells and found through a hash map on packed tile coordinates.
// NaN marks a never-observed cell, so "observed" costs no extra memory and the update loop
// learns it from the value it loads anyway. A cone update first scans the cone into rows (each
// row: its cells and, within them, the free run; sonar_cone.cpp) and then runs a branch-free,
// vectorised loop over each row piece within a tile; tiles are looked up once per cone through a
// small table over the cone's tiles. The row and tile buffers are kept between calls, so a warm
// update allocates nothing.

#if defined(__GNUC__)
#define IRGS_ALWAYS_INLINE __attribute__((always_inline))
#else
#define IRGS_ALWAYS_INLINE
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

// Cells are updated in aligned groups of kLanes: a row piece [a, b] is widened to whole groups
// and the cells outside it are written back unchanged, so the loop has no remainder whose
// varying length would cost a branch misprediction per run (short cones have many short runs).
// A tile row (kTileSize cells) is a whole number of groups, so groups never leave the tile.
constexpr int kLanes = 4;
static_assert(OccupancyGrid::kTileSize % kLanes == 0);

// Updates the cells of groups [begin, end) that lie in [a, b] (the others are written back
// unchanged): those in [fa, fb] (may be empty or reach outside [a, b]) by free_delta, the others
// by occupied_delta. Returns how many updated cells were unobserved. Branch free, so that the
// compiler vectorises it.
inline std::uint32_t updateMasked(float* cells, int begin, int end, int a, int b, int fa, int fb,
                                  float free_delta, float occupied_delta, float lo, float hi) {
  std::uint32_t fresh = 0;
  for (int i = begin; i < end; ++i) {
    const float v = cells[i];
    const bool unknown = std::isnan(v);
    const auto active = static_cast<std::uint32_t>((i >= a) & (i <= b));
    const float delta = ((i >= fa) & (i <= fb)) ? free_delta : occupied_delta;
    // Written as a bit blend: as `active ? updated : v` the compiler turns the write into a
    // branch and the loop stays scalar.
    const std::uint32_t keep_new = 0u - active;
    const std::uint32_t bits =
        (std::bit_cast<std::uint32_t>(updatedCell(v, unknown, delta, lo, hi)) & keep_new) |
        (std::bit_cast<std::uint32_t>(v) & ~keep_new);
    cells[i] = std::bit_cast<float>(bits);
    fresh += active & static_cast<std::uint32_t>(unknown);
  }
  return fresh;
}

// updateMasked for cells that are all in [a, b]: half the work per cell.
inline std::uint32_t updateAll(float* cells, int begin, int end, int fa, int fb, float free_delta,
                               float occupied_delta, float lo, float hi) {
  std::uint32_t fresh = 0;
  for (int i = begin; i < end; ++i) {
    const float v = cells[i];
    const bool unknown = std::isnan(v);
    const float delta = ((i >= fa) & (i <= fb)) ? free_delta : occupied_delta;
    cells[i] = updatedCell(v, unknown, delta, lo, hi);
    fresh += static_cast<std::uint32_t>(unknown);
  }
  return fresh;
}

// Updates cells [a, b] of one tile row (0 <= a <= b < kTileSize), the free ones [fa, fb] by
// free_delta, the others by occupied_delta; returns how many were unobserved. Short pieces are one
// masked pass; long ones a masked group at each end and an unmasked middle.
IRGS_ALWAYS_INLINE inline std::uint32_t updateTileRow(float* cells, int a, int b, int fa, int fb,
                                                      float free_delta, float occupied_delta,
                                                      float lo, float hi) {
  const int begin = a & ~(kLanes - 1);
  const int end = (b | (kLanes - 1)) + 1;
  if (end - begin <= 4 * kLanes)
    return updateMasked(cells, begin, end, a, b, fa, fb, free_delta, occupied_delta, lo, hi);
  return updateMasked(cells, begin, begin + kLanes, a, b, fa, fb, free_delta, occupied_delta, lo,
                      hi) +
         updateAll(cells, begin + kLanes, end - kLanes, fa, fb, free_delta, occupied_delta, lo,
                   hi) +
         updateMasked(cells, end - kLanes, end, a, b, fa, fb, free_delta, occupied_delta, lo, hi);
}

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

struct OccupancyGrid::ConeDeltas {
  float free_delta, occupied_delta, lo, hi;
};

IRGS_ALWAYS_INLINE inline void OccupancyGrid::applyConeRow(const ConeRow& r, const ConeDeltas& d) {
  const int ty = r.row >> kTileShift;
  const int row_offset = (r.row & kTileMask) * kTileSize;
  for (int col = r.col0; col <= r.col1;) {
    const int tx = col >> kTileShift;
    const int base = tx * kTileSize;
    const int run_end = std::min(r.col1, base + kTileMask);
    observed_cells_ +=
        updateTileRow(cachedTile(tx, ty) + row_offset, col - base, run_end - base, r.free0 - base,
                      r.free1 - base, d.free_delta, d.occupied_delta, d.lo, d.hi);
    col = run_end + 1;
  }
  cell_updates_ += static_cast<std::uint64_t>(r.col1 - r.col0 + 1);
}

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
  scanConeRows(cone, resolution_m_, scratch_rows_);
  if (scratch_rows_.empty())
    return;
  // Rows come ascending.
  CellRect touched{std::numeric_limits<int>::max(), scratch_rows_.front().row,
                   std::numeric_limits<int>::min(), scratch_rows_.back().row};
  for (const ConeRow& r : scratch_rows_) {
    touched.col0 = std::min(touched.col0, r.col0);
    touched.col1 = std::max(touched.col1, r.col1);
  }
  cache_tx0_ = touched.col0 >> kTileShift;
  cache_ty0_ = touched.row0 >> kTileShift;
  cache_width_ = (touched.col1 >> kTileShift) - cache_tx0_ + 1;
  const int cache_height = (touched.row1 >> kTileShift) - cache_ty0_ + 1;
  tile_cache_.assign(
      static_cast<std::size_t>(cache_width_) * static_cast<std::size_t>(cache_height), nullptr);
  const ConeDeltas deltas{static_cast<float>(model.free_log_odds),
                          static_cast<float>(model.occupied_log_odds),
                          static_cast<float>(model.clamp_min), static_cast<float>(model.clamp_max)};
  for (const ConeRow& r : scratch_rows_)
    applyConeRow(r, deltas);
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
