#include "eval/experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <ostream>

#include "eval/draw.hpp"
#include "eval/map_quality.hpp"
#include "eval/metrics.hpp"
#include "eval/plots.hpp"
#include "eval/report.hpp"
#include "eval/resources.hpp"
#include "io/graph_file.hpp"
#include "io/map_file.hpp"
#include "io/relations.hpp"
#include "io/tum.hpp"
#include "slam/mapper.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

io::OccupancyGrid ToOccupancyGrid(const slam::GridMap& map) {
  io::OccupancyGrid grid;
  grid.resolution_m = map.resolution_m();
  const slam::CellBounds b = map.Bounds();
  if (b.empty) return grid;
  grid.width = b.max.x - b.min.x + 1;
  grid.height = b.max.y - b.min.y + 1;
  grid.origin_x_m = b.min.x * grid.resolution_m;
  grid.origin_y_m = b.min.y * grid.resolution_m;
  grid.p_occ.assign(static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height),
                    io::OccupancyGrid::kUnknown);
  map.ForEachKnownCell([&](slam::CellIndex c, slam::CellCounts counts) {
    const double total = static_cast<double>(counts.hits) + static_cast<double>(counts.misses);
    if (total > 0.0) {
      grid.At(c.x - b.min.x, c.y - b.min.y) = static_cast<float>(counts.hits / total);
    }
  });
  return grid;
}

struct ModeRun {
  std::vector<TimelineRow> timeline;
  std::vector<double> kld;
  ModeSummary summary;
  std::string map_png;
};

void Progress(const ExperimentConfig& c, const std::string& line) {
  if (c.progress) *c.progress << line << std::flush;
}

ModeRun RunMode(const std::vector<Observation>& stream, const std::optional<GroundTruth>& truth,
                const std::vector<io::Relation>& relations, slam::PruningMode mode,
                const ExperimentConfig& config) {
  const std::string name = slam::PruningModeName(mode);
  const fs::path dir = fs::path(config.out_dir) / name;
  fs::create_directories(dir);
  slam::MapperConfig mc = config.mapper;
  mc.pruning.mode = mode;
  slam::Mapper mapper(mc);
  ModeRun run;
  std::optional<int> first_pass_end;
  mapper.on_observation = [&](const slam::StepStats& s) {
    TimelineRow row;
    row.obs = s.observation_index;
    row.t_s = s.stamp_s;
    row.time_ms = s.time_ms;
    row.nodes = static_cast<int>(s.nodes);
    row.edges = static_cast<int>(s.edges);
    row.gamma = s.gamma;
    row.rss_mb = CurrentRssMb().value_or(0.0);
    row.graph_bytes = s.graph_bytes;
    row.loop_closures = s.loop_closures_total;
    row.optimize_ms = s.optimize_ms;
    row.nodes_removed = s.nodes_removed_total;
    run.timeline.push_back(row);
    if (config.first_pass_s && s.stamp_s < *config.first_pass_s) first_pass_end = row.obs + 1;
  };
  const auto start = Clock::now();
  const std::size_t step = std::max<std::size_t>(1, stream.size() / 20);
  for (std::size_t i = 0; i < stream.size(); ++i) {
    mapper.AddObservation(stream[i]);
    if ((i + 1) % step == 0 || i + 1 == stream.size()) {
      std::ostringstream line;
      line << "\r  " << std::setw(13) << std::left << name << std::right << std::setw(4)
           << (100 * (i + 1) / stream.size()) << " %  scans " << (i + 1) << "/" << stream.size()
           << "  nodes " << mapper.graph().NumNodes() << "  edges "
           << mapper.graph().NumEdgesForGamma() << "  loops " << mapper.loop_closures().size()
           << "  " << std::fixed << std::setprecision(1) << Seconds(start) << " s   ";
      Progress(config, line.str());
    }
  }
  mapper.Finish();
  const double wall = Seconds(start);
  Progress(config, "\n");

  run.summary = SummarizeTimeline(run.timeline, first_pass_end);
  run.summary.wall_time_s = wall;
  run.summary.peak_rss_mb = PeakRssMb();
  if (!stream.empty()) {
    run.summary.scans_kept_pct = 100.0 * static_cast<double>(mapper.graph().NumNodes()) /
                                 static_cast<double>(mapper.observations());
  }
  for (const auto& m : mapper.marginalizations()) run.kld.push_back(m.kl_divergence);
  if (mode != slam::PruningMode::kNone) run.summary.kld = SummarizeKld(run.kld);

  // Trajectory of every scan, the graph, the map.
  std::vector<io::StampedPose> traj;
  std::vector<Pose2> est_poses;
  for (const slam::ScanPose& p : mapper.Trajectory()) {
    traj.push_back({p.stamp_s, p.T_world_robot});
    est_poses.push_back(p.T_world_robot);
  }
  io::WriteTum((dir / "trajectory.tum").string(), traj);
  io::WriteG2o((dir / "graph.g2o").string(), mapper.graph(), mapper.values());
  const io::OccupancyGrid grid = ToOccupancyGrid(mapper.map());
  io::WritePgmMap((dir / "map.pgm").string(), grid);
  const EntropyResult entropy = ComputeMapEntropy(grid);
  run.summary.map_entropy_bits = entropy.entropy_bits;
  run.summary.occupied_share = entropy.occupied_share;

  std::vector<TrajectoryOverlay> overlays;
  if (truth) {
    std::vector<Pose2> true_poses;
    for (const Observation& o : stream) true_poses.push_back(*o.T_world_robot_true);
    const AteResult ate = ComputeAte(est_poses, true_poses);
    run.summary.ate_rmse_m = ate.rmse_m;
    const Pose2 T_truth_est = AlignSE2(est_poses, true_poses);
    const BlurResult blur = ComputeBlur(grid, truth->walls, T_truth_est, true_poses);
    BlurSummary bs;
    bs.mean_cm = blur.mean_cm;
    bs.p95_cm = blur.p95_cm;
    bs.thickness = blur.thickness;
    if (blur.wall_cells > 0) bs.recall = blur.recall;
    run.summary.blur = bs;
    // Loop closures against the true poses of the nodes' scans.
    std::map<double, int> index_of_stamp;
    std::vector<Pose2> true_nodes;
    std::vector<LoopClosure> closures;
    auto node_index = [&](double stamp) {
      auto it = index_of_stamp.find(stamp);
      if (it != index_of_stamp.end()) return it->second;
      for (const Observation& o : stream) {
        if (o.stamp_s == stamp) {
          true_nodes.push_back(*o.T_world_robot_true);
          break;
        }
      }
      const int idx = static_cast<int>(true_nodes.size()) - 1;
      index_of_stamp[stamp] = idx;
      return idx;
    };
    for (const auto& lc : mapper.loop_closures()) {
      closures.push_back(
          {node_index(lc.stamp_old_s), node_index(lc.stamp_current_s), lc.T_old_current});
    }
    if (!closures.empty()) {
      const LoopClosureResult lcr = ComputeLoopClosureStats(closures, true_nodes);
      run.summary.loop_precision = lcr.precision;
    }
    overlays.push_back({TrajectoryKind::kTrue, {}});
    for (const Pose2& p : true_poses) overlays.back().poses.push_back(T_truth_est.Inverse() * p);
  }
  if (!relations.empty()) {
    std::vector<StampedPose> est;
    for (const auto& p : traj) est.push_back({p.stamp_s, p.T_world_robot});
    std::vector<Relation> rel;
    for (const auto& r : relations) rel.push_back({r.t1_s, r.t2_s, r.T_1_2});
    const RelationsResult rr = ComputeRelationsError(est, rel);
    run.summary.relations = RelationsSummary{static_cast<std::int64_t>(rr.count), rr.trans_mean_m,
                                             rr.trans_std_m, rr.rot_mean_deg, rr.rot_std_deg};
  }
  WriteTimelineCsv((dir / "timeline.csv").string(), run.timeline);
  run.map_png = name + "/map.png";
  DrawConfig draw;
  draw.pixels_per_cell = std::clamp(1600 / std::max({grid.width, grid.height, 1}), 1, 4);
  WriteMapPng((dir / "map.png").string(), grid, MakeGraphOverlay(mapper.graph(), mapper.values()),
              overlays, draw);
  return run;
}

}  // namespace

std::string RunExperiment(const std::vector<Observation>& stream,
                          const std::optional<GroundTruth>& truth, const ExperimentConfig& config) {
  const auto start = Clock::now();
  fs::create_directories(config.out_dir);
  std::vector<io::Relation> relations;
  if (config.relations_path) {
    relations = io::ReadRelations(*config.relations_path, config.relations_offset_s);
  }
  RunSummary summary;
  summary.source = config.source;
  summary.seed = config.seed;
  if (!stream.empty()) summary.log_duration_s = stream.back().stamp_s - stream.front().stamp_s;
  ModeTimelines timelines;
  std::map<std::string, std::vector<double>> kld;
  ReportPage page;
  for (slam::PruningMode mode : config.modes) {
    const std::string name = slam::PruningModeName(mode);
    ModeRun run = RunMode(stream, truth, relations, mode, config);
    summary.modes[name] = run.summary;
    timelines[name] = std::move(run.timeline);
    if (mode != slam::PruningMode::kNone) kld[name] = std::move(run.kld);
    page.maps[name] = run.map_png;
  }
  if (truth) {
    const io::OccupancyGrid walls = RasterizeWalls(truth->walls, config.mapper.grid.resolution_m);
    fs::create_directories(fs::path(config.out_dir) / "truth");
    io::WritePgmMap((fs::path(config.out_dir) / "truth" / "map.pgm").string(), walls);
    std::vector<io::StampedPose> true_traj;
    for (const Observation& o : stream) true_traj.push_back({o.stamp_s, *o.T_world_robot_true});
    io::WriteTum((fs::path(config.out_dir) / "truth" / "trajectory.tum").string(), true_traj);
  }
  const PlotResult plots = PlotTimelines(timelines, config.out_dir);
  for (const std::string& f : plots.files) page.figures.push_back(fs::path(f).filename().string());
  if (!kld.empty()) {
    const PlotResult kp = PlotKld(kld, config.out_dir);
    for (const std::string& f : kp.files) page.figures.push_back(fs::path(f).filename().string());
  }
  if (!plots.ok) Progress(config, "warning: no figures: " + plots.error + "\n");
  summary.wall_time_s = Seconds(start);
  page.summary = summary;
  page.command_line = config.command_line;
  WriteReportHtml((fs::path(config.out_dir) / "report.html").string(), page);
  WriteSummaryJson((fs::path(config.out_dir) / "summary.json").string(), summary);
  return SummaryJsonText(summary);
}

}  // namespace lifelong::eval
