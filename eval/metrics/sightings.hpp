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

class Sightings {
 public:
  explicit Sightings(double cell_m) : cell_m_(cell_m) {}

  /// A return of a scan after the change hit within one cell of (x, y) (truth frame).
  bool Hit(double x, double y) const { return Near(hit_, x, y); }
  /// A beam of a scan after the change crossed within one cell of (x, y), short of its return.
  bool Freed(double x, double y) const { return Near(free_, x, y); }
  /// The stamp of the last scan that hit the present outline or crossed a past one.
  std::optional<double> last_s;

  void AddHit(double x, double y) { hit_.insert(Key(x, y)); }
  void AddFree(double x, double y) { free_.insert(Key(x, y)); }

 private:
  std::int64_t Key(double x, double y) const;
  bool Near(const std::unordered_set<std::int64_t>& cells, double x, double y) const;

  double cell_m_;
  std::unordered_set<std::int64_t> hit_, free_;
};

/// The sightings of an object whose outline is `present` at the end and was `past` before,
/// by the first `scans` scans of `stream` stamped at or after since_s (its last change), on
/// cells of cell_m. A return within 0.1 m of a present segment hits it; a beam crosses a
/// past one up to 0.1 m short of its return (a beam without a return, to its maximum range).
Sightings CollectSightings(const std::vector<Observation>& stream, std::size_t scans,
                           double since_s, const std::vector<Segment>& present,
                           const std::vector<Segment>& past, double cell_m);

}  // namespace lifelong::eval
