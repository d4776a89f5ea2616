// The report's strip of changed objects (issue #35): per door or box that changed during the
// run, a tile of the mode's map around it, in the truth's frame, with its outline at the end
// in green and its earlier outlines in red. A map that follows the building shows black
// under the green and white under the red.
#pragma once

#include <string>

#include "eval/metrics/change_recall.hpp"
#include "sensor/pose2.hpp"
#include "types/occupancy_grid.hpp"

namespace lifelong::eval {

/// Writes the strip as a PNG (tiles left to right in the order of `change.objects`) and
/// returns its caption: each object's name, whether the map shows it as it stands, and
/// when it was last seen.
std::string WriteChangeTiles(const std::string& path, const ChangeRecall& change,
                             const OccupancyGrid& grid, const Pose2& T_truth_est);

}  // namespace lifelong::eval
