// Crispness without ground truth: a log's scans drawn at a trajectory's poses, and the
// distinct cells their returns fall in. The same scans at poses that agree better cover fewer
// cells: a wall seen from two poses 10 cm apart is two walls. Drawn for an estimate and for
// the reference it is scored against, over the same scans, it says which of the two makes
// the sharper map; a log's corrected poses are another system's estimate, not ground truth
// (docs/results.md "Large real logs"). In the spirit of the map entropy of point clouds
// (Droeschel et al. 2014), counting cells instead of a per-point entropy.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sensor/observation.hpp"

namespace lifelong::eval {

/// Distinct cells of side resolution_m holding a return (closer than max_range_m) of
/// stream[scans[k]] drawn at poses[k] (the robot's pose; the laser mount is applied).
/// Throws std::invalid_argument when the sizes differ or resolution_m is not positive.
std::int64_t ScanCells(const std::vector<Observation>& stream,
                       const std::vector<std::size_t>& scans, const std::vector<Pose2>& poses,
                       double resolution_m, double max_range_m);

}  // namespace lifelong::eval
