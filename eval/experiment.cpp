#include "eval/experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <memory>
#include <ostream>
#include <sstream>

#include "eval/draw.hpp"
#include "eval/interrupt.hpp"
#include "eval/map_quality.hpp"
#include "eval/mapper_config_file.hpp"
#include "eval/metrics.hpp"
#include "eval/plots.hpp"
#include "eval/progress.hpp"
#include "eval/report.hpp"
#include "eval/report_files.hpp"
#include "eval/resources.hpp"
#include "eval/run_maps.hpp"
#include "eval/staged_output.hpp"
#include "eval/video.hpp"
#include "io/atomic_file.hpp"
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

void Progress(const ExperimentConfig& c, const std::string& line) {
  if (c.progress) *c.progress << line << std::flush;
}

void WriteMarginalizations(const std::string& path, const slam::Mapper& mapper);
void WriteSparsifications(const std::string& path, const slam::Mapper& mapper);

// One mode: its mapper, its timeline and, at the end, its outputs and metrics.
class ModeRunner {
 public:
  ModeRunner(slam::PruningMode mode, const ExperimentConfig& config)
      : mode_(mode), name_(slam::PruningModeName(mode)), config_(config) {
    slam::MapperConfig mc = config.mapper;
    mc.pruning.mode = mode;
    mapper_ = std::make_unique<slam::Mapper>(mc);
    mapper_->on_observation = [this](const slam::StepStats& s) { Record(s); };
  }

  const std::string& name() const { return name_; }
  const slam::Mapper& mapper() const { return *mapper_; }
  /// Frees the mapper once the mode is finished and written.
  void Release() { mapper_.reset(); }

  void Step(const Observation& obs) {
    const auto start = Clock::now();
    mapper_->AddObservation(obs);
    seconds_ += Seconds(start);
  }

  /// Counts for the progress line.
  std::string ProgressDetail() const {
    std::ostringstream line;
    line << "nodes " << mapper_->graph().NumNodes() << "  edges "
         << mapper_->graph().NumEdgesForGamma() << "  loops " << mapper_->loop_closures().size();
    return line.str();
  }

  // Finishes the mapper, writes DIR/<mode>/... and returns the mode's summary.
  ModeSummary Finish(const std::vector<Observation>& stream,
                     const std::optional<GroundTruth>& truth,
                     const std::vector<Relation>& relations, std::vector<double>* kld,
                     std::string* map_png);

 private:
  void Record(const slam::StepStats& s) {
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
    timeline_.push_back(row);
    if (config_.first_pass_s && s.stamp_s < *config_.first_pass_s) first_pass_end_ = row.obs + 1;
  }

  /// Writes <mode>/loops.csv (one row per accepted closure, with its truth when known)
  /// and the precision over the last hour of runs longer than one.
  void WriteLoopsCsv(const LoopClosureResult& truth, ModeSummary* summary) const;

  /// Returns the ATE alignment T_truth_est (the map figures are drawn in the truth frame).
  Pose2 TruthMetrics(const std::vector<Observation>& stream, const GroundTruth& truth,
                     const std::vector<Pose2>& estimate, const OccupancyGrid& grid,
                     ModeSummary* summary) const;

  slam::PruningMode mode_;
  std::string name_;
  const ExperimentConfig& config_;
  std::unique_ptr<slam::Mapper> mapper_;
  std::vector<TimelineRow> timeline_;
  std::optional<int> first_pass_end_;
  double seconds_ = 0.0;

 public:
  const std::vector<TimelineRow>& timeline() const { return timeline_; }
};

void ModeRunner::WriteLoopsCsv(const LoopClosureResult& truth, ModeSummary* summary) const {
  const std::vector<bool>& correct = truth.correct_each;
  std::string text = "stamp_current_s,stamp_old_s,injected,correct,error_m,error_deg\n";
  const auto& loops = mapper_->loop_closures();
  const double end = timeline_.empty() ? 0.0 : timeline_.back().t_s;
  const double start = timeline_.empty() ? 0.0 : timeline_.front().t_s;
  int last_hour = 0, last_hour_correct = 0;
  char line[160];
  for (std::size_t k = 0; k < loops.size(); ++k) {
    const bool known = k < correct.size();
    if (known) {
      std::snprintf(line, sizeof(line), "%.6f,%.6f,%d,%d,%.4f,%.3f\n", loops[k].stamp_current_s,
                    loops[k].stamp_old_s, loops[k].injected ? 1 : 0, correct[k] ? 1 : 0,
                    truth.error_m_each[k], truth.error_deg_each[k]);
    } else {
      std::snprintf(line, sizeof(line), "%.6f,%.6f,%d,,,\n", loops[k].stamp_current_s,
                    loops[k].stamp_old_s, loops[k].injected ? 1 : 0);
    }
    text += line;
    if (known && loops[k].stamp_current_s >= end - 3600.0) {
      ++last_hour;
      last_hour_correct += correct[k] ? 1 : 0;
    }
  }
  if (summary && end - start > 3600.0 && last_hour > 0) {
    summary->loop_precision_last_hour = static_cast<double>(last_hour_correct) / last_hour;
  }
  io::WriteFileAtomically((fs::path(config_.out_dir) / name_ / "loops.csv").string(), text);
}

Pose2 ModeRunner::TruthMetrics(const std::vector<Observation>& stream, const GroundTruth& truth,
                               const std::vector<Pose2>& estimate, const OccupancyGrid& grid,
                               ModeSummary* summary) const {
  std::vector<Pose2> true_poses;
  std::map<double, Pose2> true_at;
  for (const Observation& o : stream) {
    true_poses.push_back(*o.T_world_robot_true);
    true_at[o.stamp_s] = *o.T_world_robot_true;
  }
  const AteResult ate = ComputeAte(estimate, true_poses);
  summary->ate_rmse_m = ate.rmse_m;
  const Pose2 T_truth_est = AlignSE2(estimate, true_poses);
  const BlurResult blur = ComputeBlur(grid, truth.walls, T_truth_est, true_poses);
  BlurSummary bs;
  bs.mean_cm = blur.mean_cm;
  bs.p95_cm = blur.p95_cm;
  bs.thickness = blur.thickness;
  if (blur.wall_cells > 0) bs.recall = blur.recall;
  summary->blur = bs;
  // Loop closures against the true poses of the observations (every node ever created,
  // in creation order: the timeline has one row per observation).
  std::map<double, int> index_of_stamp;
  std::vector<Pose2> true_nodes;
  for (const TimelineRow& row : timeline_) {
    index_of_stamp.emplace(row.t_s, static_cast<int>(true_nodes.size()));
    true_nodes.push_back(true_at.at(row.t_s));
  }
  std::vector<LoopClosure> closures;
  for (const auto& lc : mapper_->loop_closures()) {
    closures.push_back({index_of_stamp.at(lc.stamp_old_s), index_of_stamp.at(lc.stamp_current_s),
                        lc.T_old_current});
  }
  const LoopClosureResult lcr = ComputeLoopClosureStats(closures, true_nodes);
  if (lcr.accepted > 0) summary->loop_precision = lcr.precision;
  if (lcr.revisit_nodes > 0) summary->loop_recall = lcr.recall;
  WriteLoopsCsv(lcr, summary);
  return T_truth_est;
}

ModeSummary ModeRunner::Finish(const std::vector<Observation>& stream,
                               const std::optional<GroundTruth>& truth,
                               const std::vector<Relation>& relations, std::vector<double>* kld,
                               std::string* map_png) {
  const auto start = Clock::now();
  mapper_->Finish();
  seconds_ += Seconds(start);
  const fs::path dir = fs::path(config_.out_dir) / name_;
  fs::create_directories(dir);
  const slam::Mapper& m = *mapper_;

  ModeSummary summary = SummarizeTimeline(timeline_, first_pass_end_);
  summary.wall_time_s = seconds_;
  summary.peak_rss_mb = PeakRssMb();
  if (m.observations() > 0) {
    summary.scans_kept_pct =
        100.0 * static_cast<double>(m.graph().NumNodes()) / static_cast<double>(m.observations());
  }
  summary.edges_by_kind = EdgesByKind(m.graph());
  for (const auto& rec : m.marginalizations()) kld->push_back(rec.kl_divergence);
  if (mode_ != slam::PruningMode::kNone) summary.kld = SummarizeKld(*kld);

  const std::vector<StampedPose> trajectory = m.Trajectory();
  std::vector<Pose2> estimate;
  for (const StampedPose& p : trajectory) estimate.push_back(p.T_world_robot);
  io::WriteTum((dir / "trajectory.tum").string(), trajectory);
  io::WriteG2o((dir / "graph.g2o").string(), m.graph(), m.values());
  const OccupancyGrid grid = ToOccupancyGrid(m.map());
  io::WritePgmMap((dir / "map.pgm").string(), grid);
  const EntropyResult entropy = ComputeMapEntropy(grid);
  summary.map_entropy_bits = entropy.entropy_bits;
  summary.occupied_share = entropy.occupied_share;

  const slam::LoopVerifierStats& lv = m.loop_verification();
  summary.loop_verification = LoopVerificationSummary{
      lv.proposed, lv.accepted, lv.rejected, lv.expired, lv.injected, lv.injected_accepted};
  std::optional<Pose2> T_truth_est;
  if (truth) T_truth_est = TruthMetrics(stream, *truth, estimate, grid, &summary);
  if (!truth) WriteLoopsCsv(LoopClosureResult{}, nullptr);
  if (!relations.empty()) {
    const RelationsResult rr = ComputeRelationsError(trajectory, relations);
    summary.relations = RelationsSummary{static_cast<std::int64_t>(rr.count), rr.trans_mean_m,
                                         rr.trans_std_m, rr.rot_mean_deg, rr.rot_std_deg};
  }
  WriteTimelineCsv((dir / "timeline.csv").string(), timeline_);
  if (mode_ != slam::PruningMode::kNone) {
    WriteMarginalizations((dir / "marginalizations.csv").string(), m);
    WriteSparsifications((dir / "sparsifications.csv").string(), m);
  }
  WriteModeFigures(config_.out_dir, name_, grid, MakeGraphOverlay(m.graph(), m.values()),
                   T_truth_est,
                   MakeRunMapFrame(stream, truth ? &truth->walls : nullptr, grid.resolution_m));
  *map_png = name_ + "/map.png";
  return summary;
}

// Renders one frame with every mode side by side.
void AddVideoFrame(VideoSink* sink, const Observation& obs, const std::optional<GroundTruth>& truth,
                   const std::vector<std::unique_ptr<ModeRunner>>& runners) {
  std::vector<render::Panel> panels;
  for (const auto& r : runners) {
    const slam::Mapper& m = r->mapper();
    const Pose2 estimate = m.LastScanPose().T_world_robot;
    panels.push_back(MakePanel(r->name(), ToOccupancyGrid(m.map()), m.graph(), m.values(), estimate,
                               m.observations()));
  }
  const std::vector<Segment> walls = truth ? truth->walls : std::vector<Segment>{};
  const Pose2 pose = obs.T_world_robot_true.value_or(Pose2());
  sink->AddFrame(MakeScene(walls, pose, obs.scan, std::move(panels)));
}

void WriteTruth(const std::vector<Observation>& stream, const GroundTruth& truth,
                const ExperimentConfig& config) {
  WriteTruthFiles((fs::path(config.out_dir) / "truth").string(), stream, truth.walls,
                  config.mapper.grid.resolution_m);
}

// Writes DIR/<mode>/marginalizations.csv: one row per removed node.
void WriteMarginalizations(const std::string& path, const slam::Mapper& mapper) {
  std::string text = "node,clique_size,kl_nats,information_gain_bits\n";
  char line[128];
  for (const auto& m : mapper.marginalizations()) {
    std::snprintf(line, sizeof(line), "%lld,%zu,%.9g,%.9g\n", static_cast<long long>(m.node),
                  m.clique_size, m.kl_divergence, m.information_gain_bits);
    text += line;
  }
  io::WriteFileAtomically(path, text);
}

// Writes DIR/<mode>/sparsifications.csv: one row per edge-budget sparsification.
void WriteSparsifications(const std::string& path, const slam::Mapper& mapper) {
  std::string text = "centre,nodes,edges_before,edges_after,kl_nats\n";
  char line[128];
  for (const auto& s : mapper.sparsifications()) {
    std::snprintf(line, sizeof(line), "%lld,%zu,%zu,%zu,%.9g\n", static_cast<long long>(s.centre),
                  s.nodes, s.edges_before, s.edges_after, s.kl_divergence);
    text += line;
  }
  io::WriteFileAtomically(path, text);
}

}  // namespace

OccupancyGrid ToOccupancyGrid(const slam::GridMap& map) {
  OccupancyGrid grid;
  grid.resolution_m = map.resolution_m();
  const slam::CellBounds b = map.Bounds();
  if (b.empty) return grid;
  grid.width = b.max.x - b.min.x + 1;
  grid.height = b.max.y - b.min.y + 1;
  grid.origin_x_m = b.min.x * grid.resolution_m;
  grid.origin_y_m = b.min.y * grid.resolution_m;
  grid.p_occ.assign(static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height),
                    OccupancyGrid::kUnknown);
  map.ForEachKnownCell([&](slam::CellIndex c, slam::CellCounts counts) {
    const double total = static_cast<double>(counts.hits) + static_cast<double>(counts.misses);
    if (total > 0.0) {
      grid.At(c.x - b.min.x, c.y - b.min.y) = static_cast<float>(counts.hits / total);
    }
  });
  return grid;
}

namespace {

// Robot time from the first observation to the latest one so far (stamps may run
// backwards in real logs; the span never does).
class StreamSpan {
 public:
  explicit StreamSpan(const std::vector<Observation>& stream) : stream_(stream) {}
  double Covered(std::size_t done) {
    for (; seen_ < done; ++seen_) {
      lo_ = std::min(lo_, stream_[seen_].stamp_s);
      hi_ = std::max(hi_, stream_[seen_].stamp_s);
    }
    return seen_ == 0 ? 0.0 : hi_ - lo_;
  }

 private:
  const std::vector<Observation>& stream_;
  std::size_t seen_ = 0;
  double lo_ = std::numeric_limits<double>::infinity();
  double hi_ = -std::numeric_limits<double>::infinity();
};

ProgressOptions MeterOptions(const ExperimentConfig& c, const std::string& label) {
  ProgressOptions o;
  o.label = label;
  o.unit = "scans";
  o.terminal = c.progress_terminal;
  return o;
}

}  // namespace

RunSummary RunExperiment(const std::vector<Observation>& stream,
                         const std::optional<GroundTruth>& truth,
                         const ExperimentConfig& final_config) {
  const auto start = Clock::now();
  StagedOutput output(final_config.out_dir);
  ExperimentConfig config = final_config;
  config.out_dir = output.path();
  io::WriteFileAtomically((fs::path(config.out_dir) / "config.yaml").string(),
                          "# Mapper settings of this run (lifelong --config format)\n" +
                              MapperConfigToYaml(config.mapper));
  const std::vector<Relation>& relations = config.relations;
  std::unique_ptr<VideoSink> sink;
  if (!config.video_path.empty() || !config.frames_dir.empty()) {
    VideoOptions options;
    options.video_path = config.video_path;
    options.frames_dir = config.frames_dir;
    options.stride = config.video_stride;
    sink = std::make_unique<VideoSink>(options);
    Progress(config, "rendering with " + sink->backend_name() + "\n");
  }
  std::vector<std::unique_ptr<ModeRunner>> runners;
  for (slam::PruningMode mode : config.modes) {
    runners.push_back(std::make_unique<ModeRunner>(mode, config));
  }
  const std::size_t n = stream.size();
  RunSummary summary;
  summary.source = config.source;
  summary.seed = config.seed;
  summary.log = config.log;
  StreamSpan span(stream);
  if (!stream.empty()) summary.log_duration_s = span.Covered(n);
  for (const auto& r : runners) summary.mode_order.push_back(r->name());
  ModeTimelines timelines;
  std::map<std::string, std::vector<double>> kld;
  ReportPage page;
  // Evaluates a mode, writes its outputs and frees its mapper.
  auto finish = [&](ModeRunner* r) {
    std::vector<double> kl;
    std::string map_png;
    summary.modes[r->name()] = r->Finish(stream, truth, relations, &kl, &map_png);
    timelines[r->name()] = r->timeline();
    if (!kl.empty()) kld[r->name()] = std::move(kl);
    page.maps[r->name()] = map_png;
    r->Release();
  };
  if (sink) {  // lockstep: every mode sees scan i before any sees scan i + 1
    ProgressMeter meter(config.progress, static_cast<double>(n), MeterOptions(config, "all modes"));
    for (std::size_t i = 0; i < n; ++i) {
      ThrowIfInterrupted();
      for (auto& r : runners) r->Step(stream[i]);
      if (sink->Wants(static_cast<int>(i))) AddVideoFrame(sink.get(), stream[i], truth, runners);
      meter.Update(static_cast<double>(i + 1), span.Covered(i + 1),
                   runners.front()->ProgressDetail());
    }
    sink->Close();
    meter.Finish(span.Covered(n), runners.front()->ProgressDetail());
    for (auto& r : runners) finish(r.get());
  } else {  // one mode after the other, each with its own peak RSS
    for (auto& r : runners) {
      ResetPeakRss();
      ProgressMeter meter(config.progress, static_cast<double>(n), MeterOptions(config, r->name()));
      for (std::size_t i = 0; i < n; ++i) {
        ThrowIfInterrupted();
        r->Step(stream[i]);
        meter.Update(static_cast<double>(i + 1), span.Covered(i + 1), r->ProgressDetail());
      }
      meter.Finish(span.Covered(n), r->ProgressDetail());
      finish(r.get());
    }
  }
  ThrowIfInterrupted();
  if (truth) WriteTruth(stream, *truth, config);
  PlotConfig plot_config;
  plot_config.log_time = true;  // the modes differ by orders of magnitude
  const PlotResult plots = PlotTimelines(timelines, config.out_dir, plot_config);
  if (!kld.empty()) PlotKld(kld, config.out_dir);
  if (!plots.ok) Progress(config, "warning: no figures: " + plots.error + "\n");
  ThrowIfInterrupted();
  summary.wall_time_s = Seconds(start);
  page.summary = summary;
  page.command_line = config.command_line;
  CompleteReportPage(MakeReportContext(config, stream, truth, plot_config), &page);
  WriteReportHtml((fs::path(config.out_dir) / "report.html").string(), page);
  WriteSummaryJson((fs::path(config.out_dir) / "summary.json").string(), summary);
  output.Commit();
  return summary;
}

}  // namespace lifelong::eval
