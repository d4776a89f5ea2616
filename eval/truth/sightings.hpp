// What the robot saw of a changing object after its last change (issue #35's change_recall):
// the cells of its present outline that a return hit, and the cells about its past outlines
// that a beam crossed as free space. A map can show only what the robot saw, so an object is
// judged on these cells: a desk's face toward the wall, or a place it left that no beam
// crossed since, is in no map.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_set>
#include <vector>

#include "sensor/observation.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

/// Cells of cell_m (truth frame) holding at least one point.
class CellSet {
 public:
  explicit CellSet(double cell_m) : cell_m_(cell_m) {}
  void Add(double x, double y) { cells_.insert(Key(x, y)); }
  /// A point was added within one cell of (x, y).
  bool Near(double x, double y) const;
  /// The cells holding a point.
  std::size_t Size() const { return cells_.size(); }

 private:
  std::int64_t Key(double x, double y) const;

  double cell_m_;
  std::unordered_set<std::int64_t> cells_;
};

struct Sightings {
  explicit Sightings(double cell_m) : hit(cell_m), freed(cell_m) {}

  CellSet hit;    ///< where returns of scans after the change hit the present outline
  CellSet freed;  ///< where their beams crossed a past outline, short of their return
  /// The stamp of the last scan that hit the present outline or crossed a past one.
  std::optional<double> last_s;
};

/// The sightings of an object whose outline is `present` at the end and was `past` before,
/// by the first `scans` scans of `stream` stamped at or after since_s (its last change), on
/// cells of cell_m. A return within 0.1 m of a present segment hits it; a beam crosses a
/// past one up to 0.1 m short of its return (a beam without a return, to its maximum range).
Sightings CollectSightings(const std::vector<Observation>& stream, std::size_t scans,
                           double since_s, const std::vector<Segment>& present,
                           const std::vector<Segment>& past, double cell_m);

}  // namespace lifelong::eval
