// GridMap::Move: one increment list replaced by another in a single ordered pass, touching
// only the cells whose increment differs (see grid_map.hpp).
#include <stdexcept>
#include <vector>

#include "slam/grid/cell_chunk.hpp"
#include "slam/grid/grid_map.hpp"

namespace lifelong::slam {
namespace {

bool Same(CellCounts a, CellCounts b) { return a.hits == b.hits && a.misses == b.misses; }

void CheckOrdered(const std::vector<CellUpdate>& list, std::size_t i) {
  if (i > 0 && !RowOrder(list[i - 1].cell, list[i].cell)) {
    throw std::invalid_argument("GridMap::Move: lists must be ordered by (y, x), each cell once");
  }
}

}  // namespace

void GridMap::Move(const std::vector<CellUpdate>& from, const std::vector<CellUpdate>& to,
                   std::vector<CellState>* after, std::vector<CellChange>* changed) {
  // The changes are also the undo log: kept in the map's scratch when nobody asked.
  std::vector<CellChange>& changes = changed ? *changed : move_scratch_;
  changes.clear();
  if (after) after->resize(to.size());
  Cursor cursor;
  // The cells come in row order: those in one row of one chunk are contiguous, so a run of
  // them looks its chunk up once (as ForEachInRuns does for Add and Remove).
  int run_y = 0, run_x0 = 0;
  Cell* run = nullptr;
  bool have_run = false;
  const auto cell_at = [&](CellIndex c, bool create) {
    const int x0 = chunk::Of(c.x) * chunk::kSide;
    if (!have_run || c.y != run_y || x0 != run_x0 || (create && run == nullptr)) {
      run = create ? FindOrCreate({x0, c.y}, &cursor) : Find({x0, c.y}, &cursor);
      run_y = c.y;
      run_x0 = x0;
      have_run = true;
    }
    return run ? run + (c.x - x0) : nullptr;
  };
  std::size_t i = 0, j = 0;
  try {
    while (i < from.size() || j < to.size()) {
      // The next cell in row order, from either list or both.
      const bool in_from =
          i < from.size() && (j == to.size() || !RowOrder(to[j].cell, from[i].cell));
      const bool in_to = j < to.size() && (i == from.size() || !RowOrder(from[i].cell, to[j].cell));
      if (in_from) CheckOrdered(from, i);
      if (in_to) CheckOrdered(to, j);
      const CellIndex c = in_from ? from[i].cell : to[j].cell;
      const CellCounts out = in_from ? from[i].delta : CellCounts{};
      const CellCounts in = in_to ? to[j].delta : CellCounts{};
      Cell* cell = cell_at(c, in_to);
      const std::uint32_t leaving = Touches(out) ? 1 : 0;
      if (in_from && (cell == nullptr || cell->counts.hits < out.hits ||
                      cell->counts.misses < out.misses || cell->lists < leaving)) {
        throw std::logic_error("GridMap::Move: removing counts that were never added");
      }
      if (!(in_from && in_to && Same(out, in))) {
        const CellState before{cell->counts, cell->lists};
        cell->counts.hits = cell->counts.hits - out.hits + in.hits;
        cell->counts.misses = cell->counts.misses - out.misses + in.misses;
        cell->lists = cell->lists - leaving + (Touches(in) ? 1 : 0);
        changes.push_back({c, before, {cell->counts, cell->lists}});
      }
      if (in_to && after) (*after)[j] = {cell->counts, cell->lists};
      i += in_from ? 1 : 0;
      j += in_to ? 1 : 0;
    }
  } catch (const std::exception&) {
    // All or nothing: the cells changed so far get their state back.
    for (auto it = changes.rbegin(); it != changes.rend(); ++it) {
      Cell* cell = Find(it->cell, &cursor);
      cell->counts = it->before.counts;
      cell->lists = it->before.lists;
    }
    changes.clear();
    throw;
  }
}

}  // namespace lifelong::slam
