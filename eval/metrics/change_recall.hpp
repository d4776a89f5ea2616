// Per changing object (issue #35): whether the final map shows the door or box as it stands
// at the run's end, and how long before the end the robot last saw it as it stands. Only
// what the robot saw after the object's last change is judged (sightings.hpp): the cells of
// its present outline that a return hit, and the cells of its earlier outlines (an open
// door, a box's old poses) that a beam crossed. A door that opened after the robot passed
// it for the last time, a desk's face toward the wall, a place left that no beam crossed
// since: no map can show them. The object shows its present when at least half of the
// present cells seen have an occupied map cell within 1.5 cells, and fewer than half of the
// past cells seen do. Cells within 1.5 cells of a surface standing at the end are left out
// (a door's jambs, a box's new pose over its old one). change_recall is the share of the
// objects changed during the run and seen as they stand in its last 10 minutes whose map
// shows their present state.
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

class TruthRaster;

struct ObjectPresent {
  /// The map shows its state at the end; none when the robot did not see it since its last
  /// change (then no map could).
  std::optional<bool> shows_present;
  /// End minus the last scan that saw it as it stands at the end; none: never since its last
  /// change.
  std::optional<double> since_seen_s;
  /// Of the present cells seen, the share the map shows occupied; of the past cells seen, the
  /// share it still shows (why an object fails: its new face missing, or its old one kept).
  std::optional<double> present_shown, past_shown;
  std::int64_t present_seen_cells = 0, past_seen_cells = 0;  ///< the cells those shares count
  std::vector<Segment> present, past;  ///< its outline at the end, and its earlier ones
};

struct ChangeRecall {
  std::map<std::string, ObjectPresent> objects;  ///< "door NAME" / "box NAME", changed only
  std::optional<double> recall;                  ///< over those seen in the last 600 s
  int recent = 0;                                ///< how many those are
  /// The share of the map's occupied cells that show a surface the robot saw gone: stale
  /// cells (StaleShare) on a cell of a door's or box's earlier outline that a beam crossed
  /// after the object's last change. What stands in a room the robot has not looked into
  /// since is not counted: no map could know it is gone. Given a raster only.
  std::optional<double> stale_seen;
};

/// Nothing when no door or box changed during [0, end_s]. The robot has seen the first
/// `scans` observations of `stream` (all of them by default).
/// With `raster` (the run's truth at end_s, at the map's resolution) it also gives stale_seen.
std::optional<ChangeRecall> ComputeChangeRecall(const sim::World& world, double end_s,
                                                const std::vector<Observation>& stream,
                                                const OccupancyGrid& map, const Pose2& T_truth_est,
                                                std::size_t scans = SIZE_MAX,
                                                const TruthRaster* raster = nullptr);

}  // namespace lifelong::eval
