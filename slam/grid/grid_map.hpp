// Counting grid map (reflection / simple counting model, seed eq. 3.10):
//   p(c) = hits(c) / (hits(c) + misses(c)),   p = 0.5 for a cell never observed,
// and its entropy and the information gain of one scan (seed eqs. 5.10, 5.11):
//   H(m) = sum_c -p log2 p - (1-p) log2 (1-p)        (bits; an unknown cell is 1 bit)
//   I(z_i) = H(m without z_i) - H(m).
// Each scan's contribution is a list of per-cell increments (TouchedCells), so a scan can be
// added, subtracted bit-exactly or moved without rebuilding the map. Cell (x, y) covers
// [x * res, (x + 1) * res) x [y * res, (y + 1) * res) in the world frame.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "slam/grid/beam_cut.hpp"

namespace lifelong::slam {

struct CellIndex {
  int x = 0;
  int y = 0;
  bool operator==(const CellIndex& o) const { return x == o.x && y == o.y; }
};

struct CellCounts {
  std::uint32_t hits = 0;    ///< beams that ended in the cell
  std::uint32_t misses = 0;  ///< beams that passed through the cell
};

/// One scan's increment of one cell (summed over all beams of that scan).
struct CellUpdate {
  CellIndex cell;
  CellCounts delta;
};

/// The order of TouchedCells' lists: by row (y), then column (x).
inline bool RowOrder(CellIndex a, CellIndex b) { return a.y < b.y || (a.y == b.y && a.x < b.x); }

/// Whether an increment touches its cell: nonzero (what CellState::lists counts).
inline bool Touches(CellCounts delta) { return delta.hits != 0 || delta.misses != 0; }

/// A cell as a change of the map left it: its counts, and how many of the increment lists
/// in the map touch it (scans, for TouchedCells' lists).
struct CellState {
  CellCounts counts;
  std::uint32_t lists = 0;
};

/// A cell that a change of the map altered: its state before and after.
struct CellChange {
  CellIndex cell;
  CellState before, after;
};

/// Inclusive cell-index box. `empty` when the map holds no counts.
struct CellBounds {
  CellIndex min;
  CellIndex max;
  bool empty = true;
  /// Grows the box to hold the box [lo, hi].
  void Extend(CellIndex lo, CellIndex hi) {
    if (empty) {
      *this = {lo, hi, false};
      return;
    }
    min = {lo.x < min.x ? lo.x : min.x, lo.y < min.y ? lo.y : min.y};
    max = {hi.x > max.x ? hi.x : max.x, hi.y > max.y ? hi.y : max.y};
  }
};

struct GridMapConfig {
  double resolution_m = 0.05;     ///< m, cell side
  double max_free_range_m = 8.0;  ///< m, "no return" beams add misses up to this range
  double max_hit_range_m = 12.0;  ///< m, returns farther than this count as "no return"
  /// A run of at most this many "no return" beams between two returns (or a return and the
  /// scan's first or last beam) is a dropout, a beam lost on a dark or shiny surface rather
  /// than open space: it clears space only up to one cell short of the nearer return. 0:
  /// every "no return" beam clears up to max_free_range_m (before 2026-12-02), so a dropout
  /// draws free space through the wall.
  int max_dropout_beams = 2;
  /// A cell one of a scan's returns fell in takes none of that scan's misses: a scan does not
  /// contradict itself within a cell. A face seen at a grazing angle holds the returns of
  /// some beams and is crossed by their neighbours on their way to returns a little farther
  /// along it; counted, those misses outvote the face's few hits. OctoMap's scan insertion
  /// prefers a scan's occupied cells over its free ones the same way (Hornung et al. 2013,
  /// OccupancyOcTreeBase::computeUpdate). On by default since 2026-12-06; false: every
  /// traversed cell before a beam's own end counts a miss, as before
  /// (docs/results.md "Changing worlds (issue #35)").
  bool hits_mask_own_misses = true;
  /// s, the map as output (ForEachPresentCell, present_view.hpp): in the pruned modes, a cell
  /// a cut beam changed relaxes from what it shows toward its long-run occupancy with this
  /// time constant since it was last observed (and a CellLedger is kept for it). 0: the map
  /// is output as it shows. The mapper's grid, gains and matching do not read it.
  double present_timescale_s = 0.0;
  /// >= 1, the shape k of how long a changed cell keeps the state it was last seen in
  /// (present_view.hpp): it keeps it until t_seen + dt with probability exp(-(dt / tau)^k).
  /// 1: a Markov chain (no memory); above 1, a cell just seen is unlikely to change at once.
  double present_shape = 1.0;
};

/// Binary entropy in bits of a cell with these counts (1 bit when unknown).
double CellEntropyBits(CellCounts counts);

/// The unit of QuantizedEntropy, in bits.
constexpr double kEntropyQuantumBits = 0x1p-40;
/// CellEntropyBits rounded to whole quanta. Information gains are sums of these integers:
/// the same in any order of the cells, and cheap (a table for the small counts of almost
/// every cell instead of two logarithms).
std::int64_t QuantizedEntropyOf(CellCounts counts);
/// QuantizedEntropyOf for hits and misses below 64, at [hits * 64 + misses].
extern const std::array<std::int64_t, 64 * 64> kSmallCountsQuantizedEntropy;
inline std::int64_t QuantizedEntropy(CellCounts counts) {
  return (counts.hits | counts.misses) < 64
             ? kSmallCountsQuantizedEntropy[counts.hits * 64 + counts.misses]
             : QuantizedEntropyOf(counts);
}

class GridMap {
 public:
  explicit GridMap(const GridMapConfig& config = {});
  ~GridMap();
  GridMap(GridMap&&) noexcept;
  GridMap& operator=(GridMap&&) noexcept;
  GridMap(const GridMap&) = delete;
  GridMap& operator=(const GridMap&) = delete;

  const GridMapConfig& config() const { return config_; }
  double resolution_m() const { return config_.resolution_m; }
  CellIndex CellOf(double x_m, double y_m) const;

  /// Cells a scan touches from T_world_robot, traced with Bresenham from the laser origin:
  /// misses along each beam, a hit in the end cell of a return; a "no return" beam adds
  /// misses up to max_free_range_m and no hit. Beams with range <= 0 are skipped. Each cell
  /// appears once, ordered by (y, x). The beams in `cuts` (ascending by beam) are traced as
  /// BeamCut says, and only they change: the others are traced as without them (a dropout
  /// stays a dropout).
  std::vector<CellUpdate> TouchedCells(const LaserScan& scan, const Pose2& T_world_robot,
                                       const std::vector<BeamCut>& cuts = {}) const;

  /// The cells a scan's returns end in, the hits of TouchedCells (without cuts), in beam
  /// order, one per return (a cell may repeat).
  std::vector<CellIndex> ReturnCells(const LaserScan& scan, const Pose2& T_world_robot) const;

  void AddScan(const LaserScan& scan, const Pose2& T_world_robot);
  /// Exactly undoes AddScan with the same arguments.
  void RemoveScan(const LaserScan& scan, const Pose2& T_world_robot);
  void MoveScan(const LaserScan& scan, const Pose2& T_world_old, const Pose2& T_world_new);
  /// Adds an increment list; with `after`, also gives the state each of its cells is left
  /// in (one per update, in its order).
  void Add(const std::vector<CellUpdate>& updates, std::vector<CellState>* after = nullptr);
  /// Throws std::logic_error when a count would go negative (the updates were never added),
  /// leaving the map unchanged (and `after` unspecified).
  void Remove(const std::vector<CellUpdate>& updates, std::vector<CellState>* after = nullptr);

  /// Replaces the increment list `from` (in the map) by `to`: the counts Remove(from) then
  /// Add(to) leave, but a cell with the same increment in both lists is only read. A scan
  /// moved by a few centimetres keeps about 60 % of its cells so. Both lists ordered by
  /// (y, x), each cell once (TouchedCells); std::invalid_argument otherwise. With `after`,
  /// the state each cell of `to` is left in, in its order; with `changed`, the cells whose
  /// state changed, ordered by (y, x). Throws std::logic_error, leaving the map's counts
  /// unchanged, when a count would go negative (`from` was never added). It pays where the
  /// changed cells are wanted (the gain index: one update of the other scans' gains instead
  /// of two); a bare move is faster as Remove then Add (MoveScan): on Intel standard's map
  /// update took 275-285 ms through Move against 205-215 ms.
  void Move(const std::vector<CellUpdate>& from, const std::vector<CellUpdate>& to,
            std::vector<CellState>* after = nullptr, std::vector<CellChange>* changed = nullptr);

  CellCounts Counts(CellIndex c) const;
  /// How many increment lists in the map touch the cell (CellState::lists).
  std::uint32_t Lists(CellIndex c) const;
  std::uint32_t Hits(CellIndex c) const { return Counts(c).hits; }
  std::uint32_t Misses(CellIndex c) const { return Counts(c).misses; }
  /// p(occ), 0.5 for an unknown cell.
  double Probability(CellIndex c) const;
  bool IsKnown(CellIndex c) const;
  /// Box of the cells with any count (recomputed by a scan over the allocated chunks).
  CellBounds Bounds() const;
  /// Box of every chunk (32 x 32 cells) the map ever allocated: a bound on Bounds(), kept
  /// as the map grows, for a check per scan.
  const CellBounds& Extent() const { return extent_; }
  /// Calls f for every cell with any count, chunk by chunk (order unspecified).
  void ForEachKnownCell(const std::function<void(CellIndex, CellCounts)>& f) const;
  std::size_t NumKnownCells() const;

  /// Seed eq. 5.10 over an inclusive cell box, in bits (unknown cells count 1 bit).
  double EntropyBits(const CellBounds& region) const;
  /// Seed eq. 5.11 for a scan currently in the map, computed over its touched cells only.
  double InformationGain(const LaserScan& scan, const Pose2& T_world_robot) const;
  /// Same, for an increment list previously added with Add().
  double InformationGain(const std::vector<CellUpdate>& updates) const;
  /// Same, in quanta of kEntropyQuantumBits: a sum of QuantizedEntropy differences.
  std::int64_t QuantizedGain(const std::vector<CellUpdate>& updates) const;

 private:
  struct Cell {
    CellCounts counts;
    std::uint32_t lists = 0;
  };
  struct Chunk;
  /// The chunks looked up recently, direct-mapped by key: consecutive cells of an update
  /// list (ordered by row) come from the few chunks the rows cross, so most lookups hit.
  struct Cursor {
    static constexpr std::size_t kSlots = 16;
    std::array<std::uint64_t, kSlots> keys;
    std::array<Chunk*, kSlots> chunks{};
    std::array<bool, kSlots> valid{};
  };
  Cell* Find(CellIndex c, Cursor* cursor) const;
  Cell* FindOrCreate(CellIndex c, Cursor* cursor);

  GridMapConfig config_;
  std::vector<CellChange> move_scratch_;  ///< Move's undo log when the caller wants none
  std::unordered_map<std::uint64_t, std::unique_ptr<Chunk>> chunks_;
  CellBounds extent_;
};

}  // namespace lifelong::slam
