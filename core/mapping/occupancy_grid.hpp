#pragma once
// A log-odds occupancy grid that grows as the robot explores (1 cm cells by default), updated
// from sonar readings with a cone inverse sensor model.
//
// Cell (col, row) covers world [col*res, (col+1)*res) x [row*res, (row+1)*res): cell (0, 0) has
// its lower-left corner at the world origin, columns grow with +x, rows with +y. Storage is a
// sparse set of 64x64-cell tiles allocated on first write. Cells hold log-odds in 16-bit fixed
// point, steps of kLogOddsStep (1/4096), so that a room at 1 cm fits in half the cache a float
// grid needs (docs/decisions/grid.md says why). The grid is a plain value: copies are deep and
// independent.

#include <cstddef>
#include <cstdint>
#include <new>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/geometry/types.hpp"
#include "core/world/raster_map.hpp"

namespace irgs {

struct ConeRow;           // core/mapping/sonar_cone.hpp
struct ConeRowEstimates;  // core/mapping/sonar_cone_scan.hpp
struct ConeScanSetup;     // core/mapping/sonar_cone_scan.hpp
struct SonarCone;         // core/mapping/sonar_cone.hpp

struct Cell {
  int col = 0;
  int row = 0;
  friend bool operator==(const Cell&, const Cell&) = default;
};

// Inverse sensor model of one sonar reading (cone): cells inside the cone closer than the range
// become more likely free; cells on the arc at the range (thickness arc_thickness_m) become more
// likely occupied. Log-odds increments are added and clamped. The grid rounds the increments and
// the clamps away from zero to its cells' steps (OccupancyGrid::kLogOddsStep: -0.4 becomes
// -1639/4096 = -0.40015); all four must lie within +-OccupancyGrid::kMaxAbsLogOdds.
struct SonarInverseModel {
  double free_log_odds = -0.4;
  double occupied_log_odds = 0.85;
  double arc_thickness_m = 0.03;
  double clamp_min = -4.0;
  double clamp_max = 4.0;
  // Readings without an echo clear free space up to this range (0 disables).
  double no_echo_free_range_m = 1.5;
};

// What is wrong with a model (non-finite increments, increments or clamps beyond
// +-OccupancyGrid::kMaxAbsLogOdds, negative thickness or range, clamp_min > clamp_max), or
// nothing when it is usable.
std::optional<std::string> sonarInverseModelError(const SonarInverseModel& model);

// Instruction sets a cone update can use. kPortable (SSE2 on x86-64, plain C++ elsewhere) runs
// everywhere; kAvx2 (16 cells / 4 doubles a step) and kAvx512 (32 cells / 8 doubles, masked
// loads and stores; AVX-512 F, BW, DQ and VL) where the CPU has them, chosen at run time. They
// give bit-identical grids: every row boundary goes through the same IEEE operations and every
// cell through the same integer ones, only more lanes at a time (tests run each one the machine
// supports against the per-cell reference).
enum class GridSimd : std::uint8_t { kPortable, kAvx2, kAvx512 };
bool gridSimdSupported(GridSimd simd);
// The widest supported one, the default of every grid.
GridSimd bestGridSimd();

class OccupancyGrid {
 public:
  // Cell indices are kept within +-kMaxCellIndex so index arithmetic never overflows
  // (+-10,000 km at 1 cm cells).
  static constexpr int kMaxCellIndex = 1 << 30;
  // Largest cone radius accepted by integrateSonar, in cells (327 m at 1 cm).
  static constexpr int kMaxConeRadiusCells = 1 << 15;
  // Cells hold log-odds as multiples of kLogOddsStep in 16 bits: at most kMaxAbsLogOdds (7.9998,
  // p within 3.4e-4 of 0 or 1) either way. Finer than any sonar model's increments by far (the
  // default ones are -0.4 and 0.85: 1639 and 3482 steps).
  static constexpr double kLogOddsStep = 1.0 / 4096.0;
  static constexpr double kMaxAbsLogOdds = 32767.0 * kLogOddsStep;

  // Throws std::invalid_argument unless resolution_m is finite and > 0.
  explicit OccupancyGrid(double resolution_m = 0.01);

  // Defined in the .cpp, where ConeRow (scratch storage) is complete.
  OccupancyGrid(const OccupancyGrid& other);
  OccupancyGrid& operator=(const OccupancyGrid& other);
  ~OccupancyGrid();
  // A moved-from grid is empty (nothing observed), with its resolution kept.
  OccupancyGrid(OccupancyGrid&& other) noexcept;
  OccupancyGrid& operator=(OccupancyGrid&& other) noexcept;

  double resolution_m() const { return resolution_m_; }

  // The instruction set integrateSonar uses (bestGridSimd() unless set; copies keep it). Throws
  // std::invalid_argument when the CPU does not support `simd`. For tests and benchmarks: the
  // results do not depend on it.
  void setSimd(GridSimd simd);
  GridSimd simd() const { return simd_; }

  // Cell containing p. Cells exist everywhere: the grid grows when written. Throws
  // std::out_of_range when p is not finite or beyond +-kMaxCellIndex cells.
  Cell cellAt(const Vec2& p) const;
  Vec2 cellCentre(const Cell& c) const;
  // True when every point within margin_m of p maps to a cell inside +-kMaxCellIndex.
  bool isAddressable(const Vec2& p, double margin_m = 0.0) const;

  // Log-odds of a cell (a multiple of kLogOddsStep), 0 for never-observed cells.
  float logOdds(const Cell& c) const;
  double probability(const Cell& c) const;
  bool observed(const Cell& c) const;

  // Integrates one sonar cone: apex at origin, boresight heading_rad, full angle beam_width_rad.
  // With echo: free up to range - arc/2, occupied on the arc. Without echo: free up to
  // model.no_echo_free_range_m (capped at range).
  //
  // Cell membership (the exact criterion, shared with the tests): with d = cellCentre - origin,
  // a = beam/2, u_r = (cos(h-a), sin(h-a)), u_l = (cos(h+a), sin(h+a)), the cell is in the beam
  // when cross(u_r, d) >= 0 and cross(d, u_l) >= 0; it is free when |d|^2 < r_free^2 and
  // occupied when r_free^2 <= |d|^2 <= (range + arc/2)^2 (echo only), r_free = max(0, range -
  // arc/2) with an echo, min(range, no_echo_free_range_m) without. Rasterised by rows (one
  // sqrt per row, none per cell), see sonar_cone.hpp.
  //
  // Throws std::invalid_argument for non-finite arguments, beam_width_rad outside (0, pi),
  // negative range, an invalid model (sonarInverseModelError), a cone radius beyond
  // kMaxConeRadiusCells or a cone reaching beyond the addressable cells.
  void integrateSonar(const Vec2& origin, double heading_rad, double beam_width_rad, double range_m,
                      bool echo, const SonarInverseModel& model);

  // The reference for integrateSonar, for tests and benchmarks only: visits every cell of the
  // cone's bounding box and classifies it with atan2/hypot (|wrap(atan2(d) - h)| <= a,
  // hypot(d) against the radii). Same arguments and exceptions as integrateSonar.
  void integrateSonarNaive(const Vec2& origin, double heading_rad, double beam_width_rad,
                           double range_m, bool echo, const SonarInverseModel& model);

  // Bounding box of all observed cells in world metres (empty box when nothing observed).
  Box2 observedBounds() const;
  // Area of observed cells (known free or occupied), m². O(1).
  double exploredArea_m2() const;
  std::uint64_t observedCellCount() const { return observed_cells_; }

  // Cells touched since the last call, as a box in cell coordinates, for incremental redraw.
  struct CellRect {
    int col0 = 0, row0 = 0, col1 = -1, row1 = -1;  // inclusive; empty when col1 < col0
    bool empty() const { return col1 < col0 || row1 < row0; }
    int width() const { return empty() ? 0 : col1 - col0 + 1; }
    int height() const { return empty() ? 0 : row1 - row0 + 1; }
    void extend(int col, int row) {
      if (empty()) {
        col0 = col1 = col;
        row0 = row1 = row;
        return;
      }
      col0 = col < col0 ? col : col0;
      col1 = col > col1 ? col : col1;
      row0 = row < row0 ? row : row0;
      row1 = row > row1 ? row : row1;
    }
    void extend(const CellRect& other) {
      if (other.empty())
        return;
      extend(other.col0, other.row0);
      extend(other.col1, other.row1);
    }
    friend bool operator==(const CellRect&, const CellRect&) = default;
  };
  CellRect takeDirtyRect();
  // Observed cells as a box in cell coordinates (empty when nothing observed).
  CellRect observedCellRect() const { return observed_rect_; }

  // Bulk read for drawing: the log-odds of rect's cells, row-major from (col0, row0) (row0 is
  // the smallest y), width() * height() values; never-observed cells are NaN. Cost is one
  // copy per tile row, so a whole 20 m x 20 m grid at 1 cm reads in a few milliseconds.
  void copyLogOdds(const CellRect& rect, std::vector<float>& out) const;

  // Exports the observed part as a raster with ROS-style values (-1, 0..100).
  RasterMap toRaster() const;

  // Number of cell updates performed since construction (for benchmarks and tests).
  std::uint64_t cellUpdates() const { return cell_updates_; }
  // Tiles allocated so far and the memory they hold (each tile is kTileSize² 16-bit cells).
  std::size_t tileCount() const { return tiles_.size(); }
  std::size_t memoryBytes() const;

  // Same resolution and the same observed cells with bit-identical log-odds (counters such as
  // cellUpdates() and the dirty rect are not compared).
  friend bool operator==(const OccupancyGrid& a, const OccupancyGrid& b);

  static constexpr int kTileShift = 6;
  static constexpr int kTileSize = 1 << kTileShift;  // cells per tile side
  static constexpr int kTileCells = kTileSize * kTileSize;

 private:
  // Tile (tx, ty) holds cells col in [tx*64, tx*64+63], row in [ty*64, ty*64+63], row-major,
  // each log-odds / kLogOddsStep, -32768 = never observed (no log-odds rounds to it). tiles_
  // owns them (inner vectors keep their buffers when the outer one grows); tile_index_ maps the
  // packed tile coordinates to a position in tiles_.
  using CellValue = std::int16_t;
  using TileKey = std::uint64_t;
  static TileKey tileKey(int tx, int ty);
  const CellValue* findTile(int tx, int ty) const;
  CellValue* findOrCreateTile(int tx, int ty);
  // A model's increments and clamps in cell steps.
  struct CellModel {
    CellValue free_delta, occupied_delta, lo, hi;
  };
  static CellModel cellModel(const SonarInverseModel& model);
  // Applies one rasterised cone row (free and occupied increments, clamped to [lo, hi]).
  struct ConeUpdater;
  void applyConeRow(const ConeRow& row, ConeUpdater& updater);
  // The cone update's row loop with AVX2 / AVX-512 (occupancy_grid.cpp; call only where
  // gridSimdSupported says so): every row of `rows` (undecided ones scanned exactly first),
  // `touched` extended by each non-empty one. Return the cells that were unobserved.
  std::uint64_t applyConeRowsAvx2(const SonarCone& cone, const ConeScanSetup& setup,
                                  ConeRowEstimates& rows, CellRect& touched, CellModel model);
  std::uint64_t applyConeRowsAvx512(const SonarCone& cone, const ConeScanSetup& setup,
                                    ConeRowEstimates& rows, CellRect& touched, CellModel model);
  // Tile (tx, ty), created if absent, through tile_slots_.
  CellValue* slotTile(int tx, int ty);
  CellValue* fillTileSlot(int tx, int ty);
  static std::size_t slotIndex(int tx, int ty);
  // True when every tile of `cells` (a cone's rows' rectangle) is in its slot (the steady state
  // once an area is mapped): the AVX cone updates then take tiles from tile_slots_ untested, with
  // no call in their loop (the rare fill's call made GCC keep the loop's values on the stack).
  bool coneTilesInSlots(const CellRect& cells) const;
  // Prefetches the cells of a small cone's bounding box (at most kMaxPrefetchLines cache lines,
  // tiles already in tile_slots_ only), so that they arrive while the rows are estimated.
  void prefetchConeBox(const ConeScanSetup& setup) const;
  // 32 KB: the boxes of cones up to ~1 m at 1 cm. Prefetching the boxes of 1.5 m cones (with
  // float cells ~1500 lines, most outside the cone) measured slower than leaving them to the
  // hardware.
  static constexpr long kMaxPrefetchLines = 500;
  void applyCell(int col, int row, int delta, int lo, int hi);
  void noteTouched(const CellRect& cells);

  double resolution_m_;
  GridSimd simd_ = bestGridSimd();
  std::uint64_t cell_updates_ = 0;
  std::uint64_t observed_cells_ = 0;
  CellRect observed_rect_;
  CellRect dirty_rect_;
  // Tile buffers start on a cache line (64 bytes): a tile row (128 bytes) is then two whole
  // lines, and no 32- or 64-byte access of the vectorised cone update straddles two of them.
  template <class T>
  struct CacheLineAllocator {
    using value_type = T;
    CacheLineAllocator() = default;
    template <class U>
    CacheLineAllocator(const CacheLineAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
      return static_cast<T*>(::operator new (n * sizeof(T), std::align_val_t{64}));
    }
    void deallocate(T* p, std::size_t n) noexcept {
      ::operator delete (p, n * sizeof(T), std::align_val_t{64});
    }
    friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) { return true; }
  };
  std::vector<std::vector<CellValue, CacheLineAllocator<CellValue>>> tiles_;
  std::unordered_map<TileKey, std::uint32_t> tile_index_;
  // A direct-mapped cache of tile pointers in front of tile_index_: kTileSlots entries indexed by
  // the low bits of (tx, ty), so that a cone's runs find their tiles without hashing (a 20 m x
  // 20 m window at 1 cm maps without collisions; beyond it a collision costs a hash lookup).
  // Tile buffers never move (tiles_ holds them by vector, and growing the outer vector moves the
  // inner ones with their buffers), so the pointers stay valid until tiles_ is replaced: copies,
  // assignments and moves empty the cache. Allocated on the first cone. Not part of the grid's
  // value.
  struct TileSlot {
    TileKey key = kNoTile;
    CellValue* tile = nullptr;
  };
  static constexpr TileKey kNoTile = TileKey{1} << 63;  // tx = INT_MIN: no tile has it
  static constexpr int kTileSlotShift = 5;
  static constexpr int kTileSlotMask = (1 << kTileSlotShift) - 1;
  static constexpr int kTileSlots = 1 << (2 * kTileSlotShift);
  std::vector<TileSlot> tile_slots_;
  // Scratch of integrateSonar (the row scan's per-row estimates), kept between calls so that a
  // cone update allocates nothing once warm. Not part of the grid's value: copies start with it
  // empty.
  std::vector<double> scan_scratch_;
};

}  // namespace irgs
