// Counting grid map: see grid_map.hpp (seed eqs. 3.10, 5.10, 5.11).
#include "slam/grid/grid_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "slam/grid/cell_chunk.hpp"

namespace lifelong::slam {

namespace {

constexpr int kChunkBits = chunk::kBits;
constexpr int kChunkSide = chunk::kSide;
constexpr int kChunkMask = chunk::kMask;
using chunk::Key;
using chunk::Of;
using chunk::Offset;

}  // namespace

struct GridMap::Chunk {
  std::array<Cell, kChunkSide * kChunkSide> cells{};
};

GridMap::GridMap(const GridMapConfig& config) : config_(config) {}
GridMap::~GridMap() = default;
GridMap::GridMap(GridMap&&) noexcept = default;
GridMap& GridMap::operator=(GridMap&&) noexcept = default;

CellIndex GridMap::CellOf(double x_m, double y_m) const {
  return {static_cast<int>(std::floor(x_m / config_.resolution_m)),
          static_cast<int>(std::floor(y_m / config_.resolution_m))};
}

namespace {

std::size_t SlotOf(std::uint64_t key) {
  // Chunk keys of neighbouring chunks differ in their low bits of x (high word) and y.
  return static_cast<std::size_t>((key >> 32) * 5u + key) & 15u;
}

}  // namespace

GridMap::Cell* GridMap::Find(CellIndex c, Cursor* cursor) const {
  static_assert(Cursor::kSlots == 16, "SlotOf masks with 15");
  const std::uint64_t key = Key(Of(c.x), Of(c.y));
  const std::size_t slot = SlotOf(key);
  if (!cursor->valid[slot] || cursor->keys[slot] != key) {
    const auto it = chunks_.find(key);
    cursor->valid[slot] = true;
    cursor->keys[slot] = key;
    cursor->chunks[slot] = it == chunks_.end() ? nullptr : it->second.get();
  }
  Chunk* chunk = cursor->chunks[slot];
  return chunk ? &chunk->cells[static_cast<std::size_t>(Offset(c))] : nullptr;
}

GridMap::Cell* GridMap::FindOrCreate(CellIndex c, Cursor* cursor) {
  const std::uint64_t key = Key(Of(c.x), Of(c.y));
  const std::size_t slot = SlotOf(key);
  if (!cursor->valid[slot] || cursor->keys[slot] != key || cursor->chunks[slot] == nullptr) {
    std::unique_ptr<Chunk>& chunk = chunks_[key];
    if (!chunk) {
      chunk = std::make_unique<Chunk>();
      const CellIndex lo{Of(c.x) * kChunkSide, Of(c.y) * kChunkSide};
      const CellIndex hi{lo.x + kChunkSide - 1, lo.y + kChunkSide - 1};
      extent_.Extend(lo, hi);
    }
    cursor->valid[slot] = true;
    cursor->keys[slot] = key;
    cursor->chunks[slot] = chunk.get();
  }
  return &cursor->chunks[slot]->cells[static_cast<std::size_t>(Offset(c))];
}

namespace {

// Calls f(update, counts) for every update, counts pointing at its cell (or null where
// lookup(cell) found no chunk). A run of consecutive updates in one row of one chunk (an
// increment list, ordered by row, is mostly such runs) looks its chunk up once: the cells
// of a chunk row are contiguous.
template <typename Lookup, typename F>
void ForEachInRuns(const std::vector<CellUpdate>& updates, Lookup&& lookup, F&& f) {
  const std::size_t n = updates.size();
  for (std::size_t i = 0; i < n;) {
    const CellIndex first = updates[i].cell;
    auto* base = lookup(first);
    const int chunk_x = Of(first.x);
    for (; i < n && updates[i].cell.y == first.y && Of(updates[i].cell.x) == chunk_x; ++i) {
      f(updates[i], base ? base + (updates[i].cell.x - first.x) : nullptr);
    }
  }
}

}  // namespace

void GridMap::Add(const std::vector<CellUpdate>& updates, std::vector<CellState>* after) {
  if (after) after->resize(updates.size());
  CellState* out = after ? after->data() : nullptr;
  Cursor cursor;
  ForEachInRuns(
      updates, [&](CellIndex c) { return FindOrCreate(c, &cursor); },
      [&out](const CellUpdate& u, Cell* c) {
        c->counts.hits += u.delta.hits;
        c->counts.misses += u.delta.misses;
        c->lists += Touches(u.delta) ? 1 : 0;
        if (out) *out++ = {c->counts, c->lists};
      });
}

void GridMap::Remove(const std::vector<CellUpdate>& updates, std::vector<CellState>* after) {
  // All or nothing: a list that was never added (or names a cell twice, so that a count would
  // go negative) has the part already removed added back before the throw.
  if (after) after->resize(updates.size());
  CellState* out = after ? after->data() : nullptr;
  Cursor cursor;
  std::size_t done = 0;
  try {
    ForEachInRuns(
        updates, [&](CellIndex c) { return Find(c, &cursor); },
        [&done, &out](const CellUpdate& u, Cell* c) {
          const std::uint32_t list = Touches(u.delta) ? 1 : 0;
          if (c == nullptr || c->counts.hits < u.delta.hits || c->counts.misses < u.delta.misses ||
              c->lists < list) {
            throw std::logic_error("GridMap::Remove: removing counts that were never added");
          }
          c->counts.hits -= u.delta.hits;
          c->counts.misses -= u.delta.misses;
          c->lists -= list;
          if (out) *out++ = {c->counts, c->lists};
          ++done;
        });
  } catch (const std::logic_error&) {
    Add(std::vector<CellUpdate>(updates.begin(),
                                updates.begin() + static_cast<std::ptrdiff_t>(done)));
    throw;
  }
}

void GridMap::AddScan(const LaserScan& scan, const Pose2& T_world_robot) {
  Add(TouchedCells(scan, T_world_robot));
}

void GridMap::RemoveScan(const LaserScan& scan, const Pose2& T_world_robot) {
  Remove(TouchedCells(scan, T_world_robot));
}

void GridMap::MoveScan(const LaserScan& scan, const Pose2& T_world_old, const Pose2& T_world_new) {
  RemoveScan(scan, T_world_old);
  AddScan(scan, T_world_new);
}

CellCounts GridMap::Counts(CellIndex c) const {
  Cursor cursor;
  const Cell* cell = Find(c, &cursor);
  return cell ? cell->counts : CellCounts{};
}

std::uint32_t GridMap::Lists(CellIndex c) const {
  Cursor cursor;
  const Cell* cell = Find(c, &cursor);
  return cell ? cell->lists : 0;
}

double GridMap::Probability(CellIndex c) const {
  const CellCounts n = Counts(c);
  if (n.hits == 0 && n.misses == 0) return 0.5;
  return static_cast<double>(n.hits) /
         (static_cast<double>(n.hits) + static_cast<double>(n.misses));
}

bool GridMap::IsKnown(CellIndex c) const {
  const CellCounts n = Counts(c);
  return n.hits != 0 || n.misses != 0;
}

void GridMap::ForEachKnownCell(const std::function<void(CellIndex, CellCounts)>& f) const {
  for (const auto& [key, chunk] : chunks_) {
    const int base_x = chunk::XOf(key) * kChunkSide;
    const int base_y = chunk::YOf(key) * kChunkSide;
    for (int i = 0; i < kChunkSide * kChunkSide; ++i) {
      const CellCounts& c = chunk->cells[static_cast<std::size_t>(i)].counts;
      if (c.hits == 0 && c.misses == 0) continue;
      f({base_x + (i & kChunkMask), base_y + (i >> kChunkBits)}, c);
    }
  }
}

CellBounds GridMap::Bounds() const {
  CellBounds b;
  ForEachKnownCell([&b](CellIndex c, CellCounts) { b.Extend(c, c); });
  return b;
}

std::size_t GridMap::NumKnownCells() const {
  std::size_t n = 0;
  ForEachKnownCell([&n](CellIndex, CellCounts) { ++n; });
  return n;
}

double GridMap::EntropyBits(const CellBounds& region) const {
  if (region.empty) return 0.0;
  double h = 0.0;
  for (int y = region.min.y; y <= region.max.y; ++y) {
    for (int x = region.min.x; x <= region.max.x; ++x) h += CellEntropyBits(Counts({x, y}));
  }
  return h;
}

std::int64_t GridMap::QuantizedGain(const std::vector<CellUpdate>& updates) const {
  std::int64_t gain = 0;
  Cursor cursor;
  ForEachInRuns(
      updates, [&](CellIndex c) { return Find(c, &cursor); },
      [&gain](const CellUpdate& u, const Cell* found) {
        const CellCounts now = found ? found->counts : CellCounts{};
        if (now.hits < u.delta.hits || now.misses < u.delta.misses) {
          throw std::logic_error("GridMap::InformationGain: the scan is not in the map");
        }
        const CellCounts without{now.hits - u.delta.hits, now.misses - u.delta.misses};
        gain += QuantizedEntropy(without) - QuantizedEntropy(now);
      });
  return gain;
}

double GridMap::InformationGain(const std::vector<CellUpdate>& updates) const {
  return static_cast<double>(QuantizedGain(updates)) * kEntropyQuantumBits;
}

double GridMap::InformationGain(const LaserScan& scan, const Pose2& T_world_robot) const {
  return InformationGain(TouchedCells(scan, T_world_robot));
}

}  // namespace lifelong::slam
