// Counting grid map: see grid_map.hpp (seed eqs. 3.10, 5.10, 5.11).
#include "slam/grid_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "slam/scratch_table.hpp"

namespace lifelong::slam {

namespace {

constexpr int kChunkBits = 5;  // 32 x 32 cells per chunk
constexpr int kChunkSide = 1 << kChunkBits;
constexpr int kChunkMask = kChunkSide - 1;

std::uint64_t ChunkKey(int chunk_x, int chunk_y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(chunk_x)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(chunk_y));
}

// Floor division by the chunk side (arithmetic shift, as GCC and Clang define it).
int ChunkOf(int cell) { return cell >> kChunkBits; }

int Offset(CellIndex c) { return ((c.y & kChunkMask) << kChunkBits) | (c.x & kChunkMask); }

// Calls f(x, y) for every cell on the Bresenham line from a to b, both inclusive.
template <typename F>
void Bresenham(CellIndex a, CellIndex b, F&& f) {
  const int dx = std::abs(b.x - a.x), dy = -std::abs(b.y - a.y);
  const int sx = a.x < b.x ? 1 : -1, sy = a.y < b.y ? 1 : -1;
  int err = dx + dy, x = a.x, y = a.y;
  while (true) {
    f(x, y);
    if (x == b.x && y == b.y) return;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y += sy;
    }
  }
}

struct Beam {
  CellIndex end;
  bool hit;
};

// Sums the beams' increments per cell, each cell once, ordered by (y, x). When the scan's
// bounding box is small, counts go into a dense scratch box kept per thread (a fresh one
// costs more in page faults and zeroing than the scan itself); each row is read back over
// the span of columns its beams touched, and zeroed for the next call. A sort otherwise.
std::vector<CellUpdate> Accumulate(CellIndex origin, const std::vector<Beam>& beams, CellIndex lo,
                                   CellIndex hi) {
  constexpr std::int64_t kMaxDenseCells = std::int64_t{1} << 21;
  const std::int64_t w = hi.x - lo.x + 1, h = hi.y - lo.y + 1;
  std::vector<CellUpdate> out;
  if (w * h <= kMaxDenseCells) {
    thread_local std::vector<CellCounts> box;  // all zero between calls
    thread_local std::vector<int> row_first, row_last;
    if (box.size() < static_cast<std::size_t>(w * h)) {
      ResizeTable(&box, static_cast<std::size_t>(w * h));  // still all zero
    }
    row_first.assign(static_cast<std::size_t>(h), static_cast<int>(w));
    row_last.assign(static_cast<std::size_t>(h), -1);
    std::size_t distinct = 0;
    for (const Beam& b : beams) {
      Bresenham(origin, b.end, [&](int x, int y) {
        const int bx = x - lo.x;
        const auto by = static_cast<std::size_t>(y - lo.y);
        CellCounts& c = box[by * static_cast<std::size_t>(w) + static_cast<std::size_t>(bx)];
        if (c.hits == 0 && c.misses == 0) ++distinct;
        ++(b.hit && x == b.end.x && y == b.end.y ? c.hits : c.misses);
        row_first[by] = std::min(row_first[by], bx);
        row_last[by] = std::max(row_last[by], bx);
      });
    }
    const auto drain = [&](bool keep) {
      for (std::size_t by = 0; by < static_cast<std::size_t>(h); ++by) {
        CellCounts* row = box.data() + by * static_cast<std::size_t>(w);
        for (int bx = row_first[by]; bx <= row_last[by]; ++bx) {
          CellCounts& c = row[bx];
          if (c.hits == 0 && c.misses == 0) continue;
          if (keep) out.push_back({{lo.x + bx, lo.y + static_cast<int>(by)}, c});
          c = CellCounts{};
        }
      }
    };
    try {
      out.reserve(distinct);  // the only step that can throw: the box must end all zero
    } catch (...) {
      drain(false);
      throw;
    }
    drain(true);
    return out;
  }
  for (const Beam& b : beams) {
    Bresenham(origin, b.end, [&](int x, int y) {
      const bool hit = b.hit && x == b.end.x && y == b.end.y;
      out.push_back({{x, y}, {hit ? 1u : 0u, hit ? 0u : 1u}});
    });
  }
  std::sort(out.begin(), out.end(), [](const CellUpdate& a, const CellUpdate& b) {
    return a.cell.y != b.cell.y ? a.cell.y < b.cell.y : a.cell.x < b.cell.x;
  });
  std::size_t n = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (n > 0 && out[n - 1].cell == out[i].cell) {
      out[n - 1].delta.hits += out[i].delta.hits;
      out[n - 1].delta.misses += out[i].delta.misses;
    } else {
      out[n++] = out[i];
    }
  }
  out.resize(n);
  return out;
}

}  // namespace

struct GridMap::Chunk {
  std::array<CellCounts, kChunkSide * kChunkSide> cells{};
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

// Per beam, how far a "no return" beam may clear: for a dropout (a run of at most
// max_dropout_beams of them between two returns, or between the scan's end and a return),
// one cell short of the nearer return; otherwise unbounded. Written into *out (reused, so the
// hot path allocates nothing once it has seen its widest scan).
void DropoutClearRanges(const LaserScan& scan, const GridMapConfig& config,
                        std::vector<double>* out) {
  const std::size_t n = scan.ranges_m.size();
  out->assign(n, std::numeric_limits<double>::infinity());
  if (config.max_dropout_beams <= 0) return;
  const auto run_max = static_cast<std::size_t>(config.max_dropout_beams);
  for (std::size_t i = 0; i < n;) {
    if (scan.IsReturn(i)) {
      ++i;
      continue;
    }
    std::size_t end = i;  // [i, end) is a run of "no return" beams
    while (end < n && !scan.IsReturn(end)) ++end;
    // At the first or last beam of the scan the one return beside the run stands for both.
    if ((i > 0 || end < n) && end - i <= run_max) {
      const double before = i > 0 ? scan.ranges_m[i - 1] : scan.ranges_m[end];
      const double after = end < n ? scan.ranges_m[end] : scan.ranges_m[i - 1];
      const double nearer = std::min(before, after);
      std::fill(out->begin() + static_cast<std::ptrdiff_t>(i),
                out->begin() + static_cast<std::ptrdiff_t>(end), nearer - config.resolution_m);
    }
    i = end;
  }
}

}  // namespace

std::vector<CellUpdate> GridMap::TouchedCells(const LaserScan& scan,
                                              const Pose2& T_world_robot) const {
  const Pose2 T_world_laser = T_world_robot * scan.T_robot_laser;
  const CellIndex origin = CellOf(T_world_laser.x, T_world_laser.y);
  thread_local std::vector<double> dropout_clear;
  DropoutClearRanges(scan, config_, &dropout_clear);
  std::vector<Beam> beams;
  beams.reserve(scan.ranges_m.size());
  CellIndex lo = origin, hi = origin;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double r = scan.ranges_m[i];
    if (!(r > 0.0)) continue;
    // Returns beyond the usable range are too sparse and too noisy to map (one beam per
    // cell at best): like "no return" beams they only clear space, up to max_free_range_m.
    const bool hit = scan.IsReturn(i) && r <= config_.max_hit_range_m;
    const double range = hit ? r : std::min({r, config_.max_free_range_m, dropout_clear[i]});
    if (!(range > 0.0)) continue;
    const double a = scan.Bearing(i);
    double x = 0.0, y = 0.0;
    T_world_laser.Apply(range * std::cos(a), range * std::sin(a), &x, &y);
    const CellIndex end = CellOf(x, y);
    beams.push_back({end, hit});
    lo = {std::min(lo.x, end.x), std::min(lo.y, end.y)};
    hi = {std::max(hi.x, end.x), std::max(hi.y, end.y)};
  }
  return Accumulate(origin, beams, lo, hi);
}

namespace {

std::size_t SlotOf(std::uint64_t key) {
  // Chunk keys of neighbouring chunks differ in their low bits of x (high word) and y.
  return static_cast<std::size_t>((key >> 32) * 5u + key) & 15u;
}

}  // namespace

CellCounts* GridMap::Find(CellIndex c, Cursor* cursor) const {
  static_assert(Cursor::kSlots == 16, "SlotOf masks with 15");
  const std::uint64_t key = ChunkKey(ChunkOf(c.x), ChunkOf(c.y));
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

CellCounts* GridMap::FindOrCreate(CellIndex c, Cursor* cursor) {
  const std::uint64_t key = ChunkKey(ChunkOf(c.x), ChunkOf(c.y));
  const std::size_t slot = SlotOf(key);
  if (!cursor->valid[slot] || cursor->keys[slot] != key || cursor->chunks[slot] == nullptr) {
    std::unique_ptr<Chunk>& chunk = chunks_[key];
    if (!chunk) chunk = std::make_unique<Chunk>();
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
    CellCounts* base = lookup(first);
    const int chunk_x = ChunkOf(first.x);
    for (; i < n && updates[i].cell.y == first.y && ChunkOf(updates[i].cell.x) == chunk_x; ++i) {
      f(updates[i], base ? base + (updates[i].cell.x - first.x) : nullptr);
    }
  }
}

}  // namespace

void GridMap::Add(const std::vector<CellUpdate>& updates) {
  Cursor cursor;
  ForEachInRuns(
      updates, [&](CellIndex c) { return FindOrCreate(c, &cursor); },
      [](const CellUpdate& u, CellCounts* c) {
        c->hits += u.delta.hits;
        c->misses += u.delta.misses;
      });
}

void GridMap::Remove(const std::vector<CellUpdate>& updates) {
  // All or nothing: a list that was never added (or names a cell twice, so that a count would
  // go negative) has the part already removed added back before the throw.
  Cursor cursor;
  std::size_t done = 0;
  try {
    ForEachInRuns(
        updates, [&](CellIndex c) { return Find(c, &cursor); },
        [&done](const CellUpdate& u, CellCounts* c) {
          if (c == nullptr || c->hits < u.delta.hits || c->misses < u.delta.misses) {
            throw std::logic_error("GridMap::Remove: removing counts that were never added");
          }
          c->hits -= u.delta.hits;
          c->misses -= u.delta.misses;
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
  const CellCounts* counts = Find(c, &cursor);
  return counts ? *counts : CellCounts{};
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
    const int base_x = static_cast<int>(static_cast<std::uint32_t>(key >> 32)) * kChunkSide;
    const int base_y = static_cast<int>(static_cast<std::uint32_t>(key)) * kChunkSide;
    for (int i = 0; i < kChunkSide * kChunkSide; ++i) {
      const CellCounts& c = chunk->cells[static_cast<std::size_t>(i)];
      if (c.hits == 0 && c.misses == 0) continue;
      f({base_x + (i & kChunkMask), base_y + (i >> kChunkBits)}, c);
    }
  }
}

CellBounds GridMap::Bounds() const {
  CellBounds b;
  ForEachKnownCell([&b](CellIndex c, CellCounts) {
    if (b.empty) {
      b = {c, c, false};
      return;
    }
    b.min = {std::min(b.min.x, c.x), std::min(b.min.y, c.y)};
    b.max = {std::max(b.max.x, c.x), std::max(b.max.y, c.y)};
  });
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
      [&gain](const CellUpdate& u, const CellCounts* found) {
        const CellCounts now = found ? *found : CellCounts{};
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
