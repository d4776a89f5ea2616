// Map quality. Against ground truth (issue #5, DESIGN.md "Metrics"): the true walls are
// rasterized at the map resolution once per run (TruthRaster), and every occupied cell of the
// estimated map, moved into the true frame by the ATE alignment T_truth_est, is scored by its
// distance to the nearest true wall. Without truth (real logs): map entropy, seed eqs. (5.8)-(5.9),
// and the occupied share.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "eval/truth/truth_raster.hpp"
#include "sensor/pose2.hpp"
#include "types/occupancy_grid.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

struct BlurConfig {
  float occupied_threshold = 0.65f;     ///< p_occ >= this counts as occupied
  double recall_tolerance_cells = 1.5;  ///< cells; a true-wall cell is recalled when an
                                        ///< occupied cell lies within this (1.5: diagonals)
  double visibility_range_m = 8.0;      ///< m; recall only counts true-wall cells within this
                                        ///< range of the true trajectory (no line-of-sight
                                        ///< test); ignored when the trajectory is empty
};

struct BlurResult {
  std::size_t occupied_cells = 0;  ///< occupied cells of the estimated map
  double mean_cm = 0.0;            ///< cm, mean distance occupied cell -> nearest true wall
  double p95_cm = 0.0;             ///< cm, 95th percentile of the same
  double wall_length_m = 0.0;      ///< m, true wall length considered (visible part)
  double thickness = 0.0;          ///< occupied cells per metre of true wall
  std::size_t wall_cells = 0;      ///< true-wall raster cells considered (visible)
  std::size_t wall_cells_recalled = 0;
  double recall = 0.0;  ///< wall_cells_recalled / wall_cells
};

/// Scores `map` against `walls`, one of truth's fields (truth.walls() or truth.walls_now()).
/// T_truth_est maps the estimate's frame into the truth frame (AteResult::T_truth_est).
/// truth's trajectory, when it has one, limits recall and thickness to the walls the robot
/// could have seen. Distances are between cell centres, so they are quantized to the
/// resolution. Throws std::invalid_argument when the map's resolution is not the raster's.
BlurResult ComputeBlur(const OccupancyGrid& map, const TruthRaster& truth,
                       const SegmentField& walls, const Pose2& T_truth_est,
                       const BlurConfig& config = {});

/// The same, rasterizing `walls` and `true_trajectory` (truth frame; {} for every wall) for
/// this call alone.
BlurResult ComputeBlur(const OccupancyGrid& map, const std::vector<Segment>& walls,
                       const Pose2& T_truth_est, const std::vector<Pose2>& true_trajectory,
                       const BlurConfig& config = {});

/// The share of the map's occupied cells that show a surface gone by the end of the run
/// (issue #35 stale_cells): within tolerance_cells of a gone surface (truth.gone(),
/// GoneSurfaces) and farther than that from every surface standing at the end
/// (truth.walls_now(), WallsAt). 0 when the map has no occupied cell or nothing is gone.
/// With `counted`, a stale cell counts only when counted(x, y) takes its centre (truth
/// frame): stale_seen_cells counts those on surfaces the robot saw gone.
double StaleShare(const OccupancyGrid& map, const TruthRaster& truth, const Pose2& T_truth_est,
                  const BlurConfig& config = {},
                  const std::function<bool(double x, double y)>& counted = {});

/// The same, rasterizing `gone` and `now` for this call alone.
double StaleShare(const OccupancyGrid& map, const std::vector<Segment>& gone,
                  const std::vector<Segment>& now, const Pose2& T_truth_est,
                  const BlurConfig& config = {});

/// The cells of `segments` (rasterized in the truth frame), leaving out those within
/// tolerance_cells of an `exclude` segment and, when `counted` is given, those whose centre it
/// refuses; and of those, how many have an occupied map cell within tolerance_cells.
struct ShownCells {
  std::size_t counted = 0;
  std::size_t shown = 0;
  /// shown / counted; nothing when no cell is counted.
  std::optional<double> Share() const {
    if (counted == 0) return std::nullopt;
    return static_cast<double>(shown) / static_cast<double>(counted);
  }
};
ShownCells CountShown(const OccupancyGrid& map, const std::vector<Segment>& segments,
                      const std::vector<Segment>& exclude, const Pose2& T_truth_est,
                      const BlurConfig& config = {},
                      const std::function<bool(double x, double y)>& counted = {});

struct EntropyResult {
  double entropy_bits = 0.0;       ///< sum over known cells of H(p) (seed eq. 5.8), bits
  std::size_t known_cells = 0;     ///< cells with p_occ >= 0; unknown cells do not count
  std::size_t occupied_cells = 0;  ///< known cells with p_occ >= occupied_threshold
  double occupied_share = 0.0;     ///< occupied_cells / known_cells
};

/// Map entropy for maps without ground truth. Unknown cells (p < 0) are left out: each
/// would add 1 bit and the map's extent is arbitrary.
EntropyResult ComputeMapEntropy(const OccupancyGrid& map, float occupied_threshold = 0.65f);

}  // namespace lifelong::eval
