// A trajectory's and its map's figures against the truth: ATE (SE(2)-aligned), RPE over 1 m,
// and, given the true walls and a map, blur and wall recall (and the present's, when the
// world changed). One function for a run's modes and for `lifelong score`, so that scoring a
// mode's own files gives that mode's figures.
#pragma once

#include <optional>
#include <vector>

#include "eval/metrics/summary.hpp"
#include "eval/truth/ground_truth.hpp"
#include "sensor/pose2.hpp"
#include "types/occupancy_grid.hpp"

namespace lifelong::eval {

/// RPE over 1 m of reference path; absent when the path is shorter than that.
std::optional<RpeSummary> Rpe1m(const std::vector<Pose2>& estimate,
                                const std::vector<Pose2>& reference);

/// Fills summary's ate_rmse_m and rpe_1m from `estimate` against `truth` (paired by index),
/// and, when `walls` and `map` are given, blur, current_blur and stale_cells of the map
/// aligned by the ATE alignment. Returns that alignment, T_truth_est.
Pose2 ScoreAgainstTruth(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth,
                        const GroundTruth* walls, const OccupancyGrid* map, ModeSummary* summary);

}  // namespace lifelong::eval
