// Per changing object (issue #35): whether the final map shows the door or box as it stands
// at the run's end, and how long before the end the robot last saw it. A closed door (or a
// box's final pose) is shown when at least half of its cells have an occupied map cell
// within 1.5 cells; an open door (or a box's earlier pose) is shown gone when fewer than
// half do. Cells within 1.5 cells of a surface standing at the end are left out (a door's
// jambs, a box's new pose over its old one). The robot saw an object at a scan when a return
// lay within 0.1 m of it, or, for an open door, when a beam passed through the doorway.
// change_recall is the share of the objects changed during the run and seen in its last
// 10 minutes whose map shows their present state.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sensor/observation.hpp"
#include "sensor/pose2.hpp"
#include "sim/world.hpp"
#include "types/occupancy_grid.hpp"

namespace lifelong::eval {

struct ObjectPresent {
  bool shows_present = false;          ///< the map shows its state at the end
  std::optional<double> since_seen_s;  ///< end minus the last scan that saw it; none: never
  std::vector<Segment> present, past;  ///< its outline at the end, and its earlier ones
};

struct ChangeRecall {
  std::map<std::string, ObjectPresent> objects;  ///< "door NAME" / "box NAME", changed only
  std::optional<double> recall;                  ///< over those seen in the last 600 s
  int recent = 0;                                ///< how many those are
};

/// Nothing when no door or box changed during [0, end_s]. The robot has seen the first
/// `scans` observations of `stream` (all of them by default).
std::optional<ChangeRecall> ComputeChangeRecall(const sim::World& world, double end_s,
                                                const std::vector<Observation>& stream,
                                                const OccupancyGrid& map, const Pose2& T_truth_est,
                                                std::size_t scans = SIZE_MAX);

}  // namespace lifelong::eval
