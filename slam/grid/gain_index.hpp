// The information gains of the pruned modes' scans, kept exact as the map changes (seed
// eq. 5.11, in quanta of kEntropyQuantumBits). The gain of scan k is a sum over its cells,
//   I(z_k) = sum_c Q(n_c - d_kc) - Q(n_c),
// so a change of the counts of cell c from b to a alters it by
//   [Q(a - d_kc) - Q(a)] - [Q(b - d_kc) - Q(b)]
// and a change elsewhere not at all. The index holds every tracked scan's cells chunk by
// chunk (32 x 32 cells) as a bitmap with its increments: a change of the map meets each
// tracked scan in a chunk with one AND of two bitmaps, and costs one term per cell the two
// share, instead of a pass over all cells of every scan it reaches. The quantized entropies
// are integers, so a gain kept up to date this way equals the gain computed afresh, bit for
// bit.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "slam/graph/pose_graph.hpp"
#include "slam/grid/cell_chunk.hpp"
#include "slam/grid/grid_map.hpp"

namespace lifelong::slam {

/// An increment list's cells grouped by 32 x 32-cell chunk: per chunk, a bitmap of the cells
/// (bit (y mod 32) * 32 + x mod 32) and where they lie in `order`, in bit order.
struct ChunkedCells {
  static constexpr int kChunkBits = chunk::kBits;
  static constexpr int kWords = (1 << (2 * kChunkBits)) / 64;
  struct Chunk {
    std::uint64_t key = 0;
    std::array<std::uint64_t, kWords> bits{};
    std::uint32_t first = 0;  ///< its first cell's place in `order`
    std::uint32_t count = 0;  ///< its cells (set bits)
  };
  std::vector<Chunk> chunks;
  std::vector<std::uint32_t> order;  ///< indices into the list, chunk by chunk, by bit

  /// Groups a list ordered by (y, x), each cell once (GridMap::TouchedCells);
  /// std::invalid_argument otherwise.
  void Assign(const std::vector<CellUpdate>& cells);

 private:
  // Assign's counting sort: chunk numbers of the cells, each chunk's first place and the
  // next free one, and where each number's chunk is in `chunks` (when it has cells).
  std::vector<std::uint32_t> numbers, start, next, slot_of;
};

/// The gain (quanta) of a scan just added to the map, from the states its cells were left in
/// (GridMap::Add): sum_c Q(a_c - d_c) - Q(a_c), with no map lookup.
std::int64_t GainOfAdded(const std::vector<CellUpdate>& cells, const std::vector<CellState>& after);

class GainIndex {
 public:
  bool Tracks(NodeId id) const { return slots_.count(id) != 0; }
  std::size_t size() const { return slots_.size(); }
  /// The tracked scans' nodes, in no particular order.
  std::vector<NodeId> Ids() const;
  /// Starts tracking a scan in the map, whose increment list is `cells` and whose gain is
  /// `gain` quanta now. Throws std::logic_error when it is tracked already.
  void Track(NodeId id, const std::vector<CellUpdate>& cells, std::int64_t gain);
  /// Stops tracking it (before its cells move or leave the map). Returns its gain.
  std::int64_t Untrack(NodeId id);
  /// The gain of a tracked scan, exact for the map as it is now.
  std::int64_t Gain(NodeId id) const;
  /// A tracked scan's increment list as Track got it: ordered by (y, x). Rebuilt from the
  /// index (a pass over its cells), which is cheaper than tracing the scan again and lets
  /// the mapper keep no list of its own.
  void Cells(NodeId id, std::vector<CellUpdate>* cells) const;
  /// Updates the tracked gains for a change of the map: `cells` were just added to it (or
  /// removed from it), leaving the counts `after` (GridMap::Add, Remove). The scan changed
  /// must not be tracked. A change costs a search of its rows and a pass over those within
  /// a bound on the tracked scans' chunks (TrackedBox), so one far from them costs little.
  void Apply(const std::vector<CellUpdate>& cells, const std::vector<CellState>& after, bool added);
  /// Same, for cells whose states changed as listed (GridMap::Move), ordered by (y, x).
  void Apply(const std::vector<CellChange>& changes);

 private:
  /// A tracked scan's cells in one chunk: the chunk's bitmap of them (ChunkedCells) and
  /// their increments, by bit. Kept small (144 bytes): Apply walks every piece of a chunk.
  struct Piece {
    std::array<std::uint64_t, ChunkedCells::kWords> bits;
    /// The increments, inside Scan::deltas, which keeps its buffer while the scan is
    /// tracked; held here so Apply reads them without first loading the scan's record.
    const void* deltas;
    std::uint32_t slot;
    /// Bytes an increment: 1 (TinyCounts), 4 (NarrowCounts) or 8 (CellCounts), the least
    /// that holds every count of the piece.
    std::uint8_t width;
  };
  /// An increment in 4 bits a count: a cell crossed by at most 15 beams of the scan, which
  /// is every cell of most pieces (those away from the scan's origin), in a quarter of the
  /// memory (and cache) of NarrowCounts.
  struct TinyCounts {
    std::uint8_t packed;  ///< hits in the high 4 bits, misses in the low 4
  };
  /// An increment in 16 bits a count: any scan of fewer than 65 536 beams fits.
  struct NarrowCounts {
    std::uint16_t hits, misses;
  };
  struct Scan {
    std::int64_t gain = 0;
    std::uint32_t cells = 0;           ///< in its list
    std::vector<std::uint8_t> deltas;  ///< its increments, piece by piece, by bit
    std::vector<std::uint64_t> keys;   ///< of its chunks
  };
  /// An increment into and out of each width (Pack's counts must fit it).
  static void Pack(CellCounts d, TinyCounts* out) {
    out->packed = static_cast<std::uint8_t>(d.hits << 4 | d.misses);
  }
  static void Pack(CellCounts d, NarrowCounts* out) {
    *out = {static_cast<std::uint16_t>(d.hits), static_cast<std::uint16_t>(d.misses)};
  }
  static void Pack(CellCounts d, CellCounts* out) { *out = d; }
  static CellCounts Unpacked(TinyCounts d) {
    return {static_cast<std::uint32_t>(d.packed >> 4), static_cast<std::uint32_t>(d.packed & 15)};
  }
  static CellCounts Unpacked(NarrowCounts d) { return {d.hits, d.misses}; }
  static CellCounts Unpacked(CellCounts d) { return d; }
  /// Calls f with the piece's increments, typed for its width.
  template <typename F>
  static decltype(auto) WithDeltas(const Piece& piece, F&& f) {
    if (piece.width == 1) return f(static_cast<const TinyCounts*>(piece.deltas));
    if (piece.width == 4) return f(static_cast<const NarrowCounts*>(piece.deltas));
    return f(static_cast<const CellCounts*>(piece.deltas));
  }
  /// Increment i of a piece (its cells' increments in bit order).
  static CellCounts DeltaOf(const Piece& piece, std::size_t i);

  std::unordered_map<std::uint64_t, std::vector<Piece>> chunks_;
  std::unordered_map<NodeId, std::uint32_t> slots_;
  std::vector<Scan> scans_;                ///< by slot
  std::vector<std::uint32_t> free_slots_;  ///< of untracked scans, for reuse
  /// The cells of a list (ordered by row) that a tracked scan's chunk may hold: the stretch
  /// [first, last) of the rows within TrackedBox(), and of those the cells it Holds.
  struct Stretch {
    std::size_t first = 0, last = 0;
    int x0 = 0, x1 = -1;  ///< the box's columns
    bool Holds(CellIndex c) const { return x0 <= c.x && c.x <= x1; }
  };
  template <typename List>
  Stretch InTrackedBox(const List& cells) const;
  /// A bound on the chunks of the tracked scans. It grows as scans are tracked and is
  /// recomputed only after as many scans left as are tracked, so it may be wider than their
  /// hull.
  const CellBounds& TrackedBox() const;
  mutable CellBounds tracked_box_;
  mutable std::size_t left_since_box_ = 0;  ///< Untracks since tracked_box_ was recomputed
  /// Keeps a changed cell, one where a gain can change, for ApplyRelevant.
  void Keep(CellIndex cell, const CellState& before, const CellState& after);
  /// Updates the tracked gains for the cells kept.
  void ApplyRelevant();

  ChunkedCells scratch_;                    ///< Track's and Apply's grouping of a list
  std::vector<std::uint8_t> piece_widths_;  ///< Track's: each piece's width...
  std::vector<std::size_t> piece_offsets_;  ///< ...and place in Scan::deltas
  /// Apply's table for the chunk at hand, by bit: the counts before and after the change,
  /// and their entropies.
  struct Changed {
    CellCounts before, after;
    std::int64_t q_before, q_after;
  };
  std::vector<Changed> changed_;
  std::vector<CellUpdate> relevant_;      ///< Keep: the cells of a change that matter...
  std::vector<Changed> relevant_states_;  ///< ...and their states
};

}  // namespace lifelong::slam
