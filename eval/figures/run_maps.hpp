// The map figures of one run at one scale and, with ground truth, in one frame: each
// mode's <mode>/map.png (grid, true path thin, graph) and graph_<mode>.png (the graph
// alone on white, as the seed's Fig. 6.6), and truth/map.png. With ground truth every
// figure covers one box of the world frame: what the laser saw from the true path, plus
// 1 m, within the truth map's bounds (a route through part of a large world is not drawn
// in a corner of it); the estimates are moved there by their ATE alignment T_truth_est.
// Without ground truth (replays) each mode keeps its own frame and is cropped to its
// known cells, but all share one scale. The truth's other files are written here too.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eval/figures/draw.hpp"
#include "eval/figures/map_figure.hpp"
#include "eval/metrics/types.hpp"
#include "sensor/observation.hpp"
#include "types/occupancy_grid.hpp"

namespace lifelong::eval {

struct RunMapFrame {
  bool truth_frame = false;      ///< figures in the world frame, on `canvas`
  Canvas canvas;                 ///< truth_frame: the truth map's extent
  double m_per_px = 0.05;        ///< m per pixel of every map figure of the run
  std::vector<Pose2> true_path;  ///< world frame; empty without ground truth
};

/// Upscaling: k = clamp(1600 / (larger side in cells), 1, 4) pixels per cell, so a map is
/// about 1600 px wide at most; m_per_px = resolution_m / k. With walls the side is the
/// canvas's: the box of every beam's end point seen from the true poses, plus 1 m, cut to
/// the truth map's extent (the walls plus 1 m); without, the odometry path's
/// bounding box plus 10 m (the laser sees beyond the path). Both depend only on what
/// every mode shares: a run makes it once, and each mode draws its figures with it as soon
/// as it is finished.
RunMapFrame MakeRunMapFrame(const std::vector<Observation>& stream,
                            const std::vector<Segment>* walls, double resolution_m);

/// Writes <out_dir>/<mode>/map.png and <out_dir>/graph_<mode>.png, and returns those two
/// paths relative to out_dir. `graph` is in the
/// mapper's frame; T_truth_est (the ATE alignment) moves grid and graph into the world
/// frame when the frame is the truth's. Throws std::runtime_error naming a file it cannot
/// write.
std::vector<std::string> WriteModeFigures(const std::string& out_dir, const std::string& mode,
                                          const OccupancyGrid& grid, const GraphOverlay& graph,
                                          const std::optional<Pose2>& T_truth_est,
                                          const RunMapFrame& frame);

/// Writes the truth map (TruthRaster::WallGrid, the true path thin) on the frame's canvas to
/// `path`.
void WriteTruthFigure(const std::string& path, const OccupancyGrid& truth_map,
                      const RunMapFrame& frame);

/// Writes the truth's files into `dir` (created): map.pgm + map.yaml (truth_map, the walls
/// rasterized: TruthRaster::WallGrid), trajectory.tum (the true pose of every scan) and
/// map.png (the truth figure on the run's frame, MakeRunMapFrame). Returns the files' names
/// relative to `dir`.
std::vector<std::string> WriteTruthFiles(const std::string& dir,
                                         const std::vector<Observation>& stream,
                                         const OccupancyGrid& truth_map, const RunMapFrame& frame);

}  // namespace lifelong::eval
