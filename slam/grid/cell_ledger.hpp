// What a pruned map no longer holds of each cell, and when a scan last observed it: the
// memory that the map as it stands now (present_view.hpp) reads. Its size follows the map's
// area, not the number of scans: a removed scan's increments and what a cut took out of a
// scan are summed into the cells they touched, where the scan was rendered then (a later
// loop closure does not move them).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "slam/grid/cell_chunk.hpp"
#include "slam/grid/grid_map.hpp"

namespace lifelong::slam {

class CellLedger {
 public:
  struct Entry {
    std::int32_t hits = 0;    ///< archived increments: removed scans' and cut beams'
    std::int32_t misses = 0;  ///< (a cut may add misses, so either may be negative)
    float seen_s = -1.0f;     ///< latest observation, s after the first; < 0: never
    bool changed = false;     ///< a cut changed the cell: the map saw it change
  };

  /// A scan stamped stamp_s is rendered in these cells: new, or moved (a cell's observation
  /// time follows the scans that show it where they are rendered now).
  void Observe(const std::vector<CellUpdate>& cells, double stamp_s);
  /// The same for cells given alone (a scan's returns, GridMap::ReturnCells).
  void Observe(const std::vector<CellIndex>& cells, double stamp_s);
  /// A scan rendered as `cells` left the map.
  void Archive(const std::vector<CellUpdate>& cells);
  /// A scan rendered as `from` is rendered as `to` instead, at the same pose (beams cut):
  /// from - to is archived, and the cells where the two differ are marked changed. Both lists
  /// ordered by (y, x), each cell once (GridMap::TouchedCells).
  void Recut(const std::vector<CellUpdate>& from, const std::vector<CellUpdate>& to);

  /// The cell's entry; nullptr when nothing was recorded for it.
  const Entry* Find(CellIndex c) const;
  /// The stamp of the entry's latest observation, s; -infinity when never observed.
  double SeenStamp(const Entry& e) const;

 private:
  using Chunk = std::array<Entry, chunk::kSide * chunk::kSide>;
  Entry& At(CellIndex c);
  /// stamp_s as Entry::seen_s (the first stamp ever seen is the origin).
  float SinceOrigin(double stamp_s);
  void Add(CellIndex c, CellCounts delta, int sign);

  std::unordered_map<std::uint64_t, std::unique_ptr<Chunk>> chunks_;
  double origin_s_ = 0.0;
  bool have_origin_ = false;
};

}  // namespace lifelong::slam
