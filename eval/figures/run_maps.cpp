#include "eval/figures/run_maps.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "eval/truth/truth_raster.hpp"
#include "io/map_file.hpp"
#include "io/tum.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

constexpr double kMaxWidthPx = 1600.0;  // px, the larger side of a map figure at most
constexpr double kMarginM = 1.0;        // m around the known (replays) or seen cells
constexpr double kLaserReachM = 10.0;   // m added to the odometry path's extent (replays)

double MetresPerPixel(double side_m, double resolution_m) {
  const double cells = std::max(side_m / resolution_m, 1.0);
  const int k = std::clamp(static_cast<int>(kMaxWidthPx / cells), 1, 4);
  return resolution_m / k;
}

struct Box {
  double x0 = std::numeric_limits<double>::max(), y0 = x0;
  double x1 = std::numeric_limits<double>::lowest(), y1 = x1;
  void Add(double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  bool empty() const { return x1 < x0; }
};

/// What the laser saw from the true poses, world frame: every beam's end point (a
/// "no return" beam's at the maximum range) and the robot itself. Every mode's known cells
/// lie there, up to its error: the figures crop to it, not to the whole world.
Box SeenBox(const std::vector<Observation>& stream) {
  Box box;
  for (const Observation& o : stream) {
    if (!o.T_world_robot_true) continue;
    const Pose2 T_world_laser = *o.T_world_robot_true * o.scan.T_robot_laser;
    box.Add(T_world_laser.x, T_world_laser.y);
    for (std::size_t i = 0; i < o.scan.ranges_m.size(); ++i) {
      const double r = std::min(static_cast<double>(o.scan.ranges_m[i]), o.scan.range_max_m);
      if (!(r > 0.0)) continue;
      double x = 0.0, y = 0.0;
      const double bearing = o.scan.Bearing(i);
      T_world_laser.Apply(r * std::cos(bearing), r * std::sin(bearing), &x, &y);
      box.Add(x, y);
    }
  }
  return box;
}

}  // namespace

RunMapFrame MakeRunMapFrame(const std::vector<Observation>& stream,
                            const std::vector<Segment>* walls, double resolution_m) {
  RunMapFrame f;
  if (walls) {
    // The truth map's extent (RasterizeWalls'), cut down to what the laser saw plus a margin.
    const Lattice truth = LatticeCovering(*walls, {}, resolution_m, kMarginM);
    Box box;
    box.Add(truth.ox, truth.oy);
    box.Add(truth.ox + truth.cols * resolution_m, truth.oy + truth.rows * resolution_m);
    const Box seen = SeenBox(stream);
    if (!seen.empty()) {
      Box cut = box;
      cut.x0 = std::max(box.x0, seen.x0 - kMarginM), cut.x1 = std::min(box.x1, seen.x1 + kMarginM);
      cut.y0 = std::max(box.y0, seen.y0 - kMarginM), cut.y1 = std::min(box.y1, seen.y1 + kMarginM);
      if (!cut.empty() && cut.y1 >= cut.y0) box = cut;
    }
    f.truth_frame = true;
    f.m_per_px = MetresPerPixel(std::max(box.x1 - box.x0, box.y1 - box.y0), resolution_m);
    f.canvas = CanvasCovering(box.x0, box.y0, box.x1, box.y1, f.m_per_px);
    for (const Observation& o : stream) {
      if (o.T_world_robot_true) f.true_path.push_back(*o.T_world_robot_true);
    }
    return f;
  }
  double x0 = std::numeric_limits<double>::max(), y0 = x0;
  double x1 = std::numeric_limits<double>::lowest(), y1 = x1;
  for (const Observation& o : stream) {
    x0 = std::min(x0, o.T_odom_robot.x), x1 = std::max(x1, o.T_odom_robot.x);
    y0 = std::min(y0, o.T_odom_robot.y), y1 = std::max(y1, o.T_odom_robot.y);
  }
  const double side_m = stream.empty() ? 0.0 : std::max(x1 - x0, y1 - y0);
  f.m_per_px = MetresPerPixel(side_m + kLaserReachM, resolution_m);
  return f;
}

std::vector<std::string> WriteModeFigures(const std::string& out_dir, const std::string& mode,
                                          const OccupancyGrid& grid, const GraphOverlay& graph,
                                          const std::optional<Pose2>& T_truth_est,
                                          const RunMapFrame& frame) {
  FigureLayers layers;
  layers.grid = &grid;
  Canvas canvas = frame.canvas;
  if (frame.truth_frame && T_truth_est) {
    layers.T_frame_grid = *T_truth_est;
    layers.graph = Transformed(*T_truth_est, graph);
    layers.trajectories.push_back({TrajectoryKind::kTrue, frame.true_path});
  } else {
    layers.graph = graph;
    canvas = CanvasOfKnownCells(grid, Pose2(), kMarginM, frame.m_per_px);
  }
  WritePng((fs::path(out_dir) / mode / "map.png").string(), RenderFigure(canvas, layers));
  FigureLayers alone;  // seed Fig. 6.6: nodes and edges, no grid
  alone.graph = std::move(layers.graph);
  alone.node_radius_px = 2.0;
  WritePng((fs::path(out_dir) / ("graph_" + mode + ".png")).string(), RenderFigure(canvas, alone));
  return {mode + "/map.png", "graph_" + mode + ".png"};
}

void WriteTruthFigure(const std::string& path, const OccupancyGrid& truth_map,
                      const RunMapFrame& frame) {
  FigureLayers layers;
  layers.grid = &truth_map;
  layers.trajectories.push_back({TrajectoryKind::kTrue, frame.true_path});
  const Canvas canvas = frame.truth_frame ? frame.canvas : CanvasOfGrid(truth_map, frame.m_per_px);
  WritePng(path, RenderFigure(canvas, layers));
}

std::vector<std::string> WriteTruthFiles(const std::string& dir,
                                         const std::vector<Observation>& stream,
                                         const OccupancyGrid& truth_map, const RunMapFrame& frame) {
  fs::create_directories(dir);
  const io::MapFilePaths map = io::WritePgmMap((fs::path(dir) / "map.pgm").string(), truth_map);
  std::vector<StampedPose> poses;
  for (const Observation& o : stream) {
    if (o.T_world_robot_true) poses.push_back({o.stamp_s, *o.T_world_robot_true});
  }
  io::WriteTum((fs::path(dir) / "trajectory.tum").string(), poses);
  WriteTruthFigure((fs::path(dir) / "map.png").string(), truth_map, frame);
  return {fs::path(map.pgm).filename().string(), fs::path(map.yaml).filename().string(),
          "trajectory.tum", "map.png"};
}

}  // namespace lifelong::eval
