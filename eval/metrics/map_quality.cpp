#include "eval/metrics/map_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "eval/metrics/metrics.hpp"

namespace lifelong::eval {
namespace {

/// The occupied cells' centres of `map`, moved into the truth frame by T.
std::vector<std::pair<double, double>> OccupiedCentres(const OccupancyGrid& map, const Pose2& T,
                                                       float threshold) {
  std::vector<std::pair<double, double>> pts;
  for (int row = 0; row < map.height; ++row) {
    for (int col = 0; col < map.width; ++col) {
      if (map.At(col, row) < threshold) continue;
      double x = 0.0, y = 0.0;
      T.Apply(map.origin_x_m + (col + 0.5) * map.resolution_m,
              map.origin_y_m + (row + 0.5) * map.resolution_m, &x, &y);
      pts.emplace_back(x, y);
    }
  }
  return pts;
}

std::vector<LatticeCell> CellsOf(const Lattice& l,
                                 const std::vector<std::pair<double, double>>& pts) {
  std::vector<LatticeCell> cells;
  cells.reserve(pts.size());
  for (const auto& [x, y] : pts) cells.push_back(l.CellOf(x, y));
  return cells;
}

void CheckResolution(const OccupancyGrid& map, const TruthRaster& truth) {
  if (!truth.Fits(map)) {
    throw std::invalid_argument(
        "map quality: the map's resolution (" + std::to_string(map.resolution_m) +
        " m) is not the truth raster's (" + std::to_string(truth.lattice().res) + " m)");
  }
}

/// Recall and thickness: the walls' cells within the visibility range of the true path, and
/// those with an occupied cell (occ_distance) within the tolerance.
void ScoreWallCells(const TruthRaster& truth, const SegmentField& walls,
                    const std::vector<float>& occ_distance, const BlurConfig& config,
                    BlurResult* out) {
  const Lattice& l = truth.lattice();
  std::size_t all_wall_cells = 0;
  for (int row = 0; row < l.rows; ++row) {
    for (int col = 0; col < l.cols; ++col) {
      const LatticeCell c{col, row};
      if (!walls.Holds(c)) continue;
      ++all_wall_cells;
      if (truth.has_trajectory() && truth.TrajectoryDistanceM(c) > config.visibility_range_m) {
        continue;
      }
      ++out->wall_cells;
      if (occ_distance.empty() || occ_distance[l.Index(c)] > config.recall_tolerance_cells)
        continue;
      ++out->wall_cells_recalled;
    }
  }
  out->wall_length_m = walls.length_m() * static_cast<double>(out->wall_cells) /
                       static_cast<double>(std::max<std::size_t>(all_wall_cells, 1));
  if (out->wall_length_m > 0.0) {
    out->thickness = static_cast<double>(out->occupied_cells) / out->wall_length_m;
  }
  if (out->wall_cells > 0) {
    out->recall =
        static_cast<double>(out->wall_cells_recalled) / static_cast<double>(out->wall_cells);
  }
}

}  // namespace

BlurResult ComputeBlur(const OccupancyGrid& map, const TruthRaster& truth,
                       const SegmentField& walls, const Pose2& T_truth_est,
                       const BlurConfig& config) {
  CheckResolution(map, truth);
  BlurResult out;
  if (walls.empty()) return out;
  const Lattice& l = truth.lattice();
  const std::vector<LatticeCell> occ =
      CellsOf(l, OccupiedCentres(map, T_truth_est, config.occupied_threshold));
  std::vector<double> dist_cm;
  dist_cm.reserve(occ.size());
  for (const LatticeCell& c : occ) dist_cm.push_back(walls.DistanceCells(c) * l.res * 100.0);
  out.occupied_cells = occ.size();
  if (!dist_cm.empty()) {
    double sum = 0.0;
    for (double d : dist_cm) sum += d;
    out.mean_cm = sum / static_cast<double>(dist_cm.size());
    out.p95_cm = Percentile(dist_cm, 0.95);
  }
  ScoreWallCells(truth, walls, DistanceToCells(l, occ), config, &out);
  return out;
}

BlurResult ComputeBlur(const OccupancyGrid& map, const std::vector<Segment>& walls,
                       const Pose2& T_truth_est, const std::vector<Pose2>& true_trajectory,
                       const BlurConfig& config) {
  GroundTruth truth;
  truth.walls = walls;
  const TruthRaster raster(truth, true_trajectory, map.resolution_m);
  return ComputeBlur(map, raster, raster.walls(), T_truth_est, config);
}

double StaleShare(const OccupancyGrid& map, const TruthRaster& truth, const Pose2& T_truth_est,
                  const BlurConfig& config,
                  const std::function<bool(double x, double y)>& counted) {
  CheckResolution(map, truth);
  const std::vector<std::pair<double, double>> occ =
      OccupiedCentres(map, T_truth_est, config.occupied_threshold);
  if (occ.empty() || truth.gone().empty()) return 0.0;
  std::size_t stale = 0;
  for (const auto& [x, y] : occ) {
    const LatticeCell c = truth.lattice().CellOf(x, y);
    const bool near_gone = truth.gone().DistanceCells(c) <= config.recall_tolerance_cells;
    const bool near_now = truth.walls_now().DistanceCells(c) <= config.recall_tolerance_cells;
    stale += (near_gone && !near_now && (!counted || counted(x, y))) ? 1 : 0;
  }
  return static_cast<double>(stale) / static_cast<double>(occ.size());
}

double StaleShare(const OccupancyGrid& map, const std::vector<Segment>& gone,
                  const std::vector<Segment>& now, const Pose2& T_truth_est,
                  const BlurConfig& config) {
  GroundTruth truth;
  truth.walls = now;
  truth.walls.insert(truth.walls.end(), gone.begin(), gone.end());
  truth.walls_now = now;
  truth.gone = gone;
  return StaleShare(map, TruthRaster(truth, {}, map.resolution_m), T_truth_est, config);
}

ShownCells CountShown(const OccupancyGrid& map, const std::vector<Segment>& segments,
                      const std::vector<Segment>& exclude, const Pose2& T_truth_est,
                      const BlurConfig& config,
                      const std::function<bool(double x, double y)>& counted) {
  ShownCells out;
  if (segments.empty()) return out;
  const double res = map.resolution_m;
  const Lattice l = LatticeCovering(segments, {}, res, (config.recall_tolerance_cells + 2.0) * res);
  const std::vector<float> occ_dist =
      DistanceToCells(l, CellsOf(l, OccupiedCentres(map, T_truth_est, config.occupied_threshold)));
  const SegmentField cells(l, segments);
  const SegmentField excluded(l, exclude);
  for (int row = 0; row < l.rows; ++row) {
    for (int col = 0; col < l.cols; ++col) {
      const LatticeCell c{col, row};
      if (!cells.Holds(c)) continue;
      if (excluded.DistanceCells(c) <= config.recall_tolerance_cells) continue;
      if (counted && !counted(l.CentreX(col), l.CentreY(row))) continue;
      ++out.counted;
      out.shown += (!occ_dist.empty() && occ_dist[l.Index(c)] <= config.recall_tolerance_cells);
    }
  }
  return out;
}

EntropyResult ComputeMapEntropy(const OccupancyGrid& map, float occupied_threshold) {
  EntropyResult out;
  for (float p : map.p_occ) {
    if (p < 0.0f) continue;
    ++out.known_cells;
    if (p >= occupied_threshold) ++out.occupied_cells;
    const double q = static_cast<double>(p);
    if (q > 0.0 && q < 1.0) out.entropy_bits -= q * std::log2(q) + (1.0 - q) * std::log2(1.0 - q);
  }
  if (out.known_cells > 0) {
    out.occupied_share =
        static_cast<double>(out.occupied_cells) / static_cast<double>(out.known_cells);
  }
  return out;
}

}  // namespace lifelong::eval
