// The index of tracked scans by chunk (gain_index.hpp).
#include "slam/grid/gain_index.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "slam/grid/cell_chunk.hpp"

namespace lifelong::slam {

namespace {

constexpr int kBits = ChunkedCells::kChunkBits;
using chunk::Key;

int BitOf(CellIndex c) { return chunk::Offset(c); }

// How many bits of `word` lie below bit b. (Inlined into Apply, and so into its POPCNT
// clone.)
inline __attribute__((always_inline)) int Rank(std::uint64_t word, int b) {
  return __builtin_popcountll(word & ((std::uint64_t{1} << b) - 1));
}

CellCounts Minus(CellCounts a, CellCounts b) { return {a.hits - b.hits, a.misses - b.misses}; }
CellCounts Plus(CellCounts a, CellCounts b) { return {a.hits + b.hits, a.misses + b.misses}; }

// Whether no scan's gain can change in a cell in this state: its counts are pure (hits
// only or misses only) and at least two lists touch it, so each term Q(n - d_k) - Q(n) is
// Q(pure, nonzero) - Q(pure, nonzero) = 0 - 0, whichever list k is. That is almost every
// cell of free space.
bool GainsFlatAt(CellCounts counts, std::uint32_t lists) {
  return (counts.hits == 0 || counts.misses == 0) && lists >= 2;
}

// Whether a change of a cell from `before` to `after` leaves every gain as it was (checked
// for every cell of a change, so kept inline: the rest of the work is for the few others).
inline bool NoGainCanChange(const CellState& before, const CellState& after) {
  return GainsFlatAt(after.counts, after.lists) && GainsFlatAt(before.counts, before.lists);
}

}  // namespace

void ChunkedCells::Assign(const std::vector<CellUpdate>& cells) {
  chunks.clear();
  order.resize(cells.size());
  if (cells.empty()) return;
  // Chunks of the list's box, numbered row by row; a counting sort by that number keeps
  // each chunk's cells in list order, which is bit order within a chunk.
  int x0 = cells.front().cell.x, x1 = x0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const CellIndex c = cells[i].cell;
    if (i > 0 && !RowOrder(cells[i - 1].cell, c)) {
      throw std::invalid_argument("ChunkedCells: cells must be ordered by (y, x), each once");
    }
    x0 = std::min(x0, c.x);
    x1 = std::max(x1, c.x);
  }
  const int cx0 = x0 >> kBits, cy0 = cells.front().cell.y >> kBits;
  const auto width = static_cast<std::size_t>((x1 >> kBits) - cx0 + 1);
  const auto height = static_cast<std::size_t>((cells.back().cell.y >> kBits) - cy0 + 1);
  const auto number = [&](CellIndex c) {
    return static_cast<std::size_t>((c.y >> kBits) - cy0) * width +
           static_cast<std::size_t>((c.x >> kBits) - cx0);
  };
  // One pass counts each chunk's cells; the chunks that have any are made, in number order;
  // a second pass places the cells and sets their bits.
  const std::size_t count = width * height;
  start.assign(count + 1, 0);
  numbers.resize(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::size_t n = number(cells[i].cell);
    numbers[i] = static_cast<std::uint32_t>(n);
    ++start[n + 1];
  }
  slot_of.resize(count);
  for (std::size_t n = 0; n < count; ++n) {
    const std::uint32_t first = start[n], cells_in = start[n + 1];
    start[n + 1] += first;
    if (cells_in == 0) continue;
    slot_of[n] = static_cast<std::uint32_t>(chunks.size());
    Chunk& chunk = chunks.emplace_back();
    chunk.key = Key(cx0 + static_cast<int>(n % width), cy0 + static_cast<int>(n / width));
    chunk.first = first;
    chunk.count = cells_in;
  }
  next.assign(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::uint32_t n = numbers[i];
    order[next[n]++] = static_cast<std::uint32_t>(i);
    const int bit = BitOf(cells[i].cell);
    chunks[slot_of[n]].bits[static_cast<std::size_t>(bit >> 6)] |= std::uint64_t{1} << (bit & 63);
  }
}

void GainIndex::Track(NodeId id, const std::vector<CellUpdate>& cells, std::int64_t gain) {
  if (Tracks(id)) throw std::logic_error("GainIndex::Track: node " + std::to_string(id) + " twice");
  std::uint32_t slot = 0;
  if (free_slots_.empty()) {
    slot = static_cast<std::uint32_t>(scans_.size());
    scans_.emplace_back();
  } else {
    slot = free_slots_.back();
    free_slots_.pop_back();
  }
  scratch_.Assign(cells);
  Scan& scan = scans_[slot];
  scan.gain = gain;
  scan.cells = static_cast<std::uint32_t>(cells.size());
  // Each piece's increments in the narrowest width that holds them, aligned for it.
  const std::uint32_t* order = scratch_.order.data();
  piece_widths_.clear();
  piece_offsets_.clear();
  std::size_t size = 0;
  for (const ChunkedCells::Chunk& chunk : scratch_.chunks) {
    std::uint32_t most = 0;
    for (std::uint32_t k = chunk.first; k < chunk.first + chunk.count; ++k) {
      const CellCounts d = cells[order[k]].delta;
      most = std::max({most, d.hits, d.misses});
    }
    const std::uint8_t width = most <= 15 ? 1 : most <= 0xffff ? 4 : 8;
    const std::size_t align = width == 1   ? 1
                              : width == 4 ? alignof(NarrowCounts)
                                           : alignof(CellCounts);
    size = (size + align - 1) / align * align;
    piece_widths_.push_back(width);
    piece_offsets_.push_back(size);
    size += std::size_t{chunk.count} * width;
  }
  scan.deltas.resize(size);
  scan.keys.clear();
  // Filled through plain pointers: push_back kept reloading the vector's end (the loop took
  // 86 % of Track's time in BM_GainIndexTrackScan).
  for (std::size_t c = 0; c < scratch_.chunks.size(); ++c) {
    const ChunkedCells::Chunk& chunk = scratch_.chunks[c];
    std::uint8_t* at = scan.deltas.data() + piece_offsets_[c];
    const std::uint32_t* from = order + chunk.first;
    const std::uint8_t width = piece_widths_[c];
    const auto fill = [&](auto* out) {
      for (std::uint32_t k = 0; k < chunk.count; ++k) Pack(cells[from[k]].delta, out + k);
    };
    if (width == 1) {
      fill(reinterpret_cast<TinyCounts*>(at));
    } else if (width == 4) {
      fill(reinterpret_cast<NarrowCounts*>(at));
    } else {
      fill(reinterpret_cast<CellCounts*>(at));
    }
    chunks_[chunk.key].push_back({chunk.bits, at, slot, width});
    scan.keys.push_back(chunk.key);
    tracked_box_.Extend(chunk::FirstCell(chunk.key), chunk::LastCell(chunk.key));
  }
  slots_.emplace(id, slot);
}

std::int64_t GainIndex::Untrack(NodeId id) {
  const auto it = slots_.find(id);
  if (it == slots_.end()) {
    throw std::logic_error("GainIndex::Untrack: node " + std::to_string(id) + " not tracked");
  }
  const std::uint32_t slot = it->second;
  Scan& scan = scans_[slot];
  for (std::uint64_t key : scan.keys) {
    const auto chunk = chunks_.find(key);
    std::vector<Piece>& pieces = chunk->second;
    const auto piece = std::find_if(pieces.begin(), pieces.end(),
                                    [slot](const Piece& p) { return p.slot == slot; });
    *piece = pieces.back();
    pieces.pop_back();
    if (pieces.empty()) chunks_.erase(chunk);
  }
  slots_.erase(it);
  free_slots_.push_back(slot);
  ++left_since_box_;
  std::vector<std::uint8_t>().swap(scan.deltas);
  return scan.gain;
}

std::vector<NodeId> GainIndex::Ids() const {
  std::vector<NodeId> ids;
  ids.reserve(slots_.size());
  for (const auto& [id, slot] : slots_) ids.push_back(id);
  return ids;
}

std::int64_t GainIndex::Gain(NodeId id) const {
  const auto it = slots_.find(id);
  if (it == slots_.end()) {
    throw std::logic_error("GainIndex::Gain: node " + std::to_string(id) + " not tracked");
  }
  return scans_[it->second].gain;
}

CellCounts GainIndex::DeltaOf(const Piece& piece, std::size_t i) {
  return WithDeltas(piece, [i](const auto* deltas) { return Unpacked(deltas[i]); });
}

void GainIndex::Cells(NodeId id, std::vector<CellUpdate>* cells) const {
  const auto it = slots_.find(id);
  if (it == slots_.end()) {
    throw std::logic_error("GainIndex::Cells: node " + std::to_string(id) + " not tracked");
  }
  const std::uint32_t slot = it->second;
  const Scan& scan = scans_[slot];
  cells->clear();
  cells->reserve(scan.cells);
  static_assert(chunk::kSide == 32, "two chunk rows per 64-bit word");
  // The scan's chunks in Track's order, which is by chunk row, then column; each with its
  // bitmap and the next of its increments to emit (bit order is row order within a chunk).
  struct Band {
    int cx, cy;
    const Piece* piece;
    std::size_t next;
  };
  std::vector<Band> bands;
  for (std::uint64_t key : scan.keys) {
    const std::vector<Piece>& pieces = chunks_.at(key);
    const Piece& piece = *std::find_if(pieces.begin(), pieces.end(),
                                       [slot](const Piece& p) { return p.slot == slot; });
    bands.push_back({chunk::XOf(key), chunk::YOf(key), &piece, 0});
  }
  for (std::size_t first = 0; first < bands.size();) {
    std::size_t last = first;  // the chunks of one chunk row: [first, last)
    while (last < bands.size() && bands[last].cy == bands[first].cy) ++last;
    for (int y = 0; y < chunk::kSide; ++y) {
      for (std::size_t b = first; b < last; ++b) {
        Band& band = bands[b];
        const std::uint64_t word = band.piece->bits[static_cast<std::size_t>(y >> 1)];
        std::uint64_t row = (word >> ((y & 1) * chunk::kSide)) & 0xffffffffu;
        while (row != 0) {
          const int x = __builtin_ctzll(row);
          row &= row - 1;
          cells->push_back({{band.cx * chunk::kSide + x, band.cy * chunk::kSide + y},
                            DeltaOf(*band.piece, band.next++)});
        }
      }
    }
    first = last;
  }
}

std::int64_t GainOfAdded(const std::vector<CellUpdate>& cells,
                         const std::vector<CellState>& after) {
  if (after.size() != cells.size())
    throw std::logic_error("GainOfAdded: one state per cell expected");
  std::int64_t gain = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const CellCounts a = after[i].counts;
    if (GainsFlatAt(a, after[i].lists)) continue;
    gain += QuantizedEntropy(Minus(a, cells[i].delta)) - QuantizedEntropy(a);
  }
  return gain;
}

const CellBounds& GainIndex::TrackedBox() const {
  // Recomputed after as many scans left as are tracked: a pass over the chunks per that many
  // Untracks, each of which visited its own chunks anyway.
  if (left_since_box_ > 0 && left_since_box_ >= slots_.size()) {
    tracked_box_ = {};
    for (const auto& entry : chunks_)
      tracked_box_.Extend(chunk::FirstCell(entry.first), chunk::LastCell(entry.first));
    left_since_box_ = 0;
  }
  return tracked_box_;
}

template <typename List>
GainIndex::Stretch GainIndex::InTrackedBox(const List& cells) const {
  if (cells.empty() || chunks_.empty()) return {};
  // The list is ordered by row: the rows within the box are one stretch of it.
  const CellBounds& box = TrackedBox();
  const int y0 = box.min.y, y1 = box.max.y;
  const auto first = std::partition_point(cells.begin(), cells.end(),
                                          [y0](const auto& u) { return u.cell.y < y0; });
  const auto last =
      std::partition_point(first, cells.end(), [y1](const auto& u) { return u.cell.y <= y1; });
  return {static_cast<std::size_t>(first - cells.begin()),
          static_cast<std::size_t>(last - cells.begin()), box.min.x, box.max.x};
}

void GainIndex::Keep(CellIndex cell, const CellState& before, const CellState& after) {
  relevant_.push_back({cell, {}});
  relevant_states_.push_back({before.counts, after.counts, QuantizedEntropy(before.counts),
                              QuantizedEntropy(after.counts)});
}

void GainIndex::Apply(const std::vector<CellUpdate>& cells, const std::vector<CellState>& after,
                      bool added) {
  if (after.size() != cells.size()) {
    throw std::logic_error("GainIndex::Apply: one state per cell expected");
  }
  // Only the cells within the tracked scans' box where a gain can change, before or after,
  // are looked up: most changes far from the robot (a loop closure moves scans across a
  // campus) hold none.
  relevant_.clear();
  relevant_states_.clear();
  const Stretch in = InTrackedBox(cells);
  for (std::size_t i = in.first; i < in.last; ++i) {
    if (!in.Holds(cells[i].cell)) continue;
    const CellCounts d = cells[i].delta;
    const CellState& a = after[i];
    const std::uint32_t touches = Touches(d) ? 1 : 0;
    const CellState before{added ? Minus(a.counts, d) : Plus(a.counts, d),
                           added ? a.lists - touches : a.lists + touches};
    if (!NoGainCanChange(before, a)) Keep(cells[i].cell, before, a);
  }
  if (!relevant_.empty()) ApplyRelevant();
}

void GainIndex::Apply(const std::vector<CellChange>& changes) {
  relevant_.clear();
  relevant_states_.clear();
  const Stretch in = InTrackedBox(changes);
  for (std::size_t i = in.first; i < in.last; ++i) {
    const CellChange& c = changes[i];
    if (in.Holds(c.cell) && !NoGainCanChange(c.before, c.after)) Keep(c.cell, c.before, c.after);
  }
  if (!relevant_.empty()) ApplyRelevant();
}

// (Cloned for CPUs with and without the POPCNT instruction: the rank of a bit in a piece
// is a population count, a library call on the x86-64 baseline. Flattened, so that the
// per-piece lambdas are compiled into each clone rather than once for the baseline.)
__attribute__((target_clones("popcnt", "default"), flatten)) void GainIndex::ApplyRelevant() {
  scratch_.Assign(relevant_);
  changed_.resize(std::size_t{1} << (2 * kBits));
  Changed* changed = changed_.data();
  for (const ChunkedCells::Chunk& chunk : scratch_.chunks) {
    const auto found = chunks_.find(chunk.key);
    if (found == chunks_.end()) continue;
    for (std::uint32_t place = chunk.first; place < chunk.first + chunk.count; ++place) {
      const std::uint32_t i = scratch_.order[place];
      changed[static_cast<std::size_t>(BitOf(relevant_[i].cell))] = relevant_states_[i];
    }
    // The increments are where the time goes, one cache miss per piece: ask for each
    // piece's first shared one before reading any, so the misses overlap.
    const std::vector<Piece>& pieces = found->second;
    for (const Piece& piece : pieces) {
      std::size_t skipped = 0;  // the piece's cells in the words before w
      for (std::size_t w = 0; w < ChunkedCells::kWords; ++w) {
        const std::uint64_t shared = chunk.bits[w] & piece.bits[w];
        if (shared != 0) {
          const std::size_t i =
              skipped + static_cast<std::size_t>(Rank(piece.bits[w], __builtin_ctzll(shared)));
          __builtin_prefetch(static_cast<const char*>(piece.deltas) + i * piece.width);
          break;
        }
        skipped += static_cast<std::size_t>(__builtin_popcountll(piece.bits[w]));
      }
    }
    // The change of one piece's gain, for either width of its increments.
    const auto change_of = [&chunk, changed](const Piece& piece, const auto* deltas) {
      std::int64_t delta = 0;
      for (std::size_t w = 0; w < ChunkedCells::kWords; ++w) {
        std::uint64_t shared = chunk.bits[w] & piece.bits[w];
        while (shared != 0) {
          const int b = __builtin_ctzll(shared);
          shared &= shared - 1;
          const Changed& c = changed[w * 64 + static_cast<std::size_t>(b)];
          const CellCounts d = Unpacked(deltas[Rank(piece.bits[w], b)]);
          delta += (QuantizedEntropy(Minus(c.after, d)) - c.q_after) -
                   (QuantizedEntropy(Minus(c.before, d)) - c.q_before);
        }
        deltas += __builtin_popcountll(piece.bits[w]);
      }
      return delta;
    };
    for (const Piece& piece : pieces) {
      const std::int64_t delta =
          WithDeltas(piece, [&](const auto* deltas) { return change_of(piece, deltas); });
      scans_[piece.slot].gain += delta;
    }
  }
}

}  // namespace lifelong::slam
