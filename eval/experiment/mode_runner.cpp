// One mode of an experiment; see mode_runner.hpp.
#include "eval/experiment/mode_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "eval/common/raster_limit.hpp"
#include "eval/common/resources.hpp"
#include "eval/common/stopwatch.hpp"
#include "eval/experiment/false_closures.hpp"
#include "eval/figures/change_tiles.hpp"
#include "eval/figures/run_maps.hpp"
#include "eval/metrics/change_recall.hpp"
#include "eval/metrics/map_quality.hpp"
#include "eval/metrics/sequential_counts.hpp"
#include "eval/metrics/trajectory_reference.hpp"
#include "eval/metrics/truth_metrics.hpp"
#include "eval/truth/scan_cells.hpp"
#include "eval/truth/truth_raster.hpp"
#include "eval/truth/world_state.hpp"
#include "io/atomic_file.hpp"
#include "io/graph_file.hpp"
#include "io/map_file.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

// A run whose map outgrows kMaxRasterCells is stopped at the observation that did, not at
// the end with the memory exhausted.
constexpr double kMaxMapCells = kMaxRasterCells;

}  // namespace

ModeRunner::ModeRunner(const slam::Mode& mode, const ExperimentConfig& config)
    : mode_(mode), name_(mode.name), config_(config) {
  slam::MapperConfig mc = config.mapper;
  mc.pruning.mode = mode;
  mapper_ = std::make_unique<slam::Mapper>(mc);
  mapper_->on_observation = [this](const slam::StepStats& s) { Record(s); };
  const FalseClosureConfig& inject = config.false_closures;
  if (inject.share > 0.0) {
    mapper_->set_hypothesis_hook(FalseClosureInjector(inject.share, inject.dx_m, inject.dy_m));
  }
}
void ModeRunner::Step(const Observation& obs) {
  const auto start = Clock::now();
  mapper_->AddObservation(obs);
  seconds_ += Seconds(start);
  const slam::CellBounds& box = mapper_->map().Extent();
  if (box.empty) return;
  const double w = box.max.x - box.min.x + 1.0, h = box.max.y - box.min.y + 1.0;
  if (w * h <= kMaxMapCells) return;
  const double r = mapper_->map().resolution_m();
  char what[320];
  std::snprintf(what, sizeof what,
                "the scan stamped %.3f s (observation %zu) takes the map to %.0f x %.0f m, "
                "more than the %.0f cells a map may hold at %g m: does the odometry jump? "
                "(a larger area needs a coarser grid.resolution_m)",
                obs.stamp_s, static_cast<std::size_t>(timeline_.back().obs), w * r, h * r,
                kMaxMapCells, r);
  throw InputError(config_.source, 0, "", what);
}

std::string ModeRunner::ProgressDetail() const {
  std::ostringstream line;
  line << "nodes " << mapper_->graph().NumNodes() << "  edges "
       << mapper_->graph().NumEdgesForGamma() << "  loops " << mapper_->loop_closures().size();
  return line.str();
}

void ModeRunner::Record(const slam::StepStats& s) {
  observation_scans_.push_back(static_cast<std::size_t>(s.scan_index));
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
  row.stages = s.stages;
  row.sequential = SequentialOutcome(s);
  row.odometry_lost = s.odometry_lost;
  timeline_.push_back(row);
  for (const slam::LoopAttempt& a : s.loop_attempts) loop_attempts_.push_back({row.obs, a});
  CountSequential(s, &sequential_);
  if (config_.first_pass_s && s.stamp_s < *config_.first_pass_s) first_pass_end_ = row.obs + 1;
}

void ModeRunner::WriteLoopsCsv(const LoopClosureResult& truth, ModeSummary* summary) const {
  const std::vector<bool>& correct = truth.correct_each;
  std::string text =
      "stamp_current_s,stamp_old_s,injected,correct,error_m,error_deg,final_chi2,node_current,"
      "node_old\n";
  const auto& loops = mapper_->loop_closures();
  const std::vector<std::optional<double>> chi2 = mapper_->LoopEdgeChi2();
  const double end = timeline_.empty() ? 0.0 : timeline_.back().t_s;
  const double start = timeline_.empty() ? 0.0 : timeline_.front().t_s;
  int last_hour = 0, last_hour_correct = 0;
  char line[160];
  for (std::size_t k = 0; k < loops.size(); ++k) {
    const bool known = k < correct.size();
    if (known) {
      std::snprintf(line, sizeof(line), "%.6f,%.6f,%d,%d,%.4f,%.3f,", loops[k].stamp_current_s,
                    loops[k].stamp_old_s, loops[k].injected ? 1 : 0, correct[k] ? 1 : 0,
                    truth.error_m_each[k], truth.error_deg_each[k]);
    } else {
      std::snprintf(line, sizeof(line), "%.6f,%.6f,%d,,,,", loops[k].stamp_current_s,
                    loops[k].stamp_old_s, loops[k].injected ? 1 : 0);
    }
    text += line;
    if (chi2[k]) {
      std::snprintf(line, sizeof(line), "%.4g", *chi2[k]);
      text += line;
    }
    text += ',' + std::to_string(loops[k].current) + ',' + std::to_string(loops[k].old) + '\n';
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
                               ModeSummary* summary) {
  std::vector<Pose2> true_poses;
  std::map<double, Pose2> true_at;
  for (const Observation& o : stream) {
    true_poses.push_back(*o.T_world_robot_true);
    true_at[o.stamp_s] = *o.T_world_robot_true;
  }
  const Pose2 T_truth_est = ScoreAgainstTruth(estimate, true_poses, &truth, &grid, summary);
  if (estimate.size() == stream.size()) {
    std::vector<std::size_t> every(stream.size());
    for (std::size_t i = 0; i < every.size(); ++i) every[i] = i;
    CountScanCells(stream, every, estimate, true_poses, summary);
  }
  if (truth.world) {
    summary->change = ComputeChangeRecall(*truth.world, truth.end_s, stream, grid, T_truth_est,
                                          SIZE_MAX, truth.raster.get());
  }
  std::vector<Pose2> true_nodes;
  for (const TimelineRow& row : timeline_) true_nodes.push_back(true_at.at(row.t_s));
  ScoreLoops(true_nodes, summary);
  return T_truth_est;
}

void ModeRunner::ScoreLoops(const std::vector<Pose2>& true_nodes, ModeSummary* summary) {
  // true_nodes[k] is the pose of the timeline's row k: every node ever created, in creation
  // order (the timeline has one row per observation, and observation k is node k). Nodes are
  // named by id, not by stamp: some logs stamp every scan alike.
  std::vector<LoopClosure> closures;
  for (const auto& lc : mapper_->loop_closures()) {
    closures.push_back({static_cast<int>(lc.old), static_cast<int>(lc.current), lc.T_old_current});
  }
  const LoopClosureResult lcr = ComputeLoopClosureStats(closures, true_nodes);
  if (lcr.accepted > 0) summary->loop_precision = lcr.precision;
  if (lcr.revisit_nodes > 0) summary->loop_recall = lcr.recall;
  WriteLoopsCsv(lcr, summary);
  loop_curve_ = LoopCurve(timeline_, lcr);
}

std::optional<std::vector<Pose2>> ModeRunner::ReferenceAtObservations(
    const std::vector<StampedPose>& trajectory) const {
  const bool per_scan = config_.reference_per_scan && trajectory.size() == config_.reference.size();
  std::vector<Pose2> nodes;     // per scan: the reference's pose of each observation's scan
  std::vector<StampedPose> at;  // else: the observations' scans, paired by stamp below
  for (const std::size_t i : observation_scans_) {
    if (i >= trajectory.size()) return std::nullopt;
    if (per_scan) {
      nodes.push_back(config_.reference[i].T_world_robot);
    } else {
      at.push_back(trajectory[i]);
    }
  }
  if (per_scan) return nodes;
  ReferencePairs pairs = PairWithReference(at, config_.reference);
  if (pairs.unmatched > 0) return std::nullopt;  // closures with no reference: not scored
  return std::move(pairs.reference);
}

void ModeRunner::ScorePresentAt(const std::vector<Observation>& stream, std::size_t i,
                                const std::optional<GroundTruth>& truth) {
  if (!truth || !truth->world) return;
  const double stamp = stream[i].stamp_s;
  for (const double t : config_.present_at_s) {
    // stream[i] is the first scan at or after t.
    if (stamp < t || (i > 0 && stream[i - 1].stamp_s >= t)) continue;
    const std::vector<StampedPose> trajectory = mapper_->Trajectory();
    std::vector<Pose2> estimate, true_poses;
    for (std::size_t k = 0; k < trajectory.size() && k <= i; ++k) {
      estimate.push_back(trajectory[k].T_world_robot);
      true_poses.push_back(*stream[k].T_world_robot_true);
    }
    const OccupancyGrid grid = ToOccupancyGrid(*mapper_);
    GroundTruth then = TruthOf(*truth->world, t);
    // One raster of the world as it stood then, for the map's figures and its stale cells.
    then.raster = std::make_shared<const TruthRaster>(then, true_poses, grid.resolution_m);
    ModeSummary s;
    const Pose2 T_truth_est = ScoreAgainstTruth(estimate, true_poses, &then, &grid, &s);
    PresentAt p;
    p.t_s = t;
    p.ate_rmse_m = s.ate_rmse_m;
    // Before anything changed the present is every wall there is.
    p.current_blur = s.current_blur ? s.current_blur : s.blur;
    p.stale_cells = s.current_blur ? s.stale_cells : 0.0;
    if (const auto change = ComputeChangeRecall(*truth->world, t, stream, grid, T_truth_est, i + 1,
                                                then.raster.get())) {
      p.change_recall = change->recall;
      p.change_recall_seen = change->recent;
      p.stale_seen_cells = change->stale_seen;
    }
    present_at_.push_back(p);
  }
}

LoopVerificationSummary ModeRunner::SummarizeLoops() const {
  const slam::Mapper& m = *mapper_;
  return LoopVerificationSummary{m.loop_verification(), config_.false_closures.share > 0.0,
                                 config_.mapper.loops.global.enabled, m.SuspectLoopEdges()};
}

void ModeRunner::CountScanCells(const std::vector<Observation>& stream,
                                const std::vector<std::size_t>& scans,
                                const std::vector<Pose2>& estimate,
                                const std::vector<Pose2>& reference, ModeSummary* summary) const {
  const slam::GridMapConfig& g = config_.mapper.grid;
  summary->scan_cells = ScanCells(stream, scans, estimate, g.resolution_m, g.max_hit_range_m);
  summary->scan_cells_reference =
      ScanCells(stream, scans, reference, g.resolution_m, g.max_hit_range_m);
}

void ModeRunner::ScoreAgainstReference(const std::vector<Observation>& stream,
                                       const std::vector<StampedPose>& trajectory,
                                       ModeSummary* summary) {
  const ReferencePairs pairs = config_.reference_per_scan
                                   ? PairScanByScan(trajectory, config_.reference)
                                   : PairWithReference(trajectory, config_.reference);
  summary->reference_matched = static_cast<std::int64_t>(pairs.estimate.size());
  if (pairs.estimate.empty()) return;
  const AteResult ate = ComputeAte(pairs.estimate, pairs.reference);
  summary->ate_rmse_m = ate.rmse_m;
  summary->rpe_1m = Rpe1m(pairs.estimate, pairs.reference);
  if (trajectory.size() == stream.size()) {
    CountScanCells(stream, pairs.index, pairs.estimate, pairs.reference, summary);
  }
  aligned_to_reference_.clear();
  for (const Pose2& p : pairs.estimate) aligned_to_reference_.push_back(ate.T_truth_est * p);
}

void ModeRunner::ScoreReference(const std::vector<Observation>& stream,
                                const std::vector<StampedPose>& trajectory, bool truth,
                                ModeSummary* summary) {
  std::optional<std::vector<Pose2>> nodes;
  if (!config_.reference.empty()) {
    ScoreAgainstReference(stream, trajectory, summary);
    nodes = ReferenceAtObservations(trajectory);
  }
  if (truth) return;  // TruthMetrics scored the closures and wrote loops.csv
  if (nodes) {
    ScoreLoops(*nodes, summary);
  } else {
    WriteLoopsCsv(LoopClosureResult{}, nullptr);
  }
}

ModeSummary ModeRunner::SummarizeRun(std::vector<double>* kld) const {
  const slam::Mapper& m = *mapper_;
  ModeSummary summary = SummarizeTimeline(timeline_, first_pass_end_);
  summary.wall_time_s = seconds_;
  summary.peak_rss_mb = PeakRssMb();
  if (m.observations() > 0) {
    summary.scans_kept_pct =
        100.0 * static_cast<double>(m.graph().NumNodes()) / static_cast<double>(m.observations());
  }
  summary.edges_by_kind = EdgesByKind(m.graph());
  if (sequential_.count > 0) summary.sequential = sequential_;
  for (const auto& rec : m.marginalizations()) kld->push_back(rec.kl_divergence);
  if (mode_.Prunes()) summary.kld = SummarizeKld(*kld);
  return summary;
}

ModeSummary ModeRunner::Finish(const std::vector<Observation>& stream,
                               const std::optional<GroundTruth>& truth,
                               const std::vector<Relation>& relations, const RunMapFrame& frame,
                               std::vector<double>* kld, std::string* map_png) {
  const auto start = Clock::now();
  mapper_->Finish();
  seconds_ += Seconds(start);
  const fs::path dir = fs::path(config_.out_dir) / name_;
  fs::create_directories(dir);
  const slam::Mapper& m = *mapper_;
  ModeSummary summary = SummarizeRun(kld);

  const std::vector<StampedPose> trajectory = m.Trajectory();
  std::vector<Pose2> estimate;
  for (const StampedPose& p : trajectory) estimate.push_back(p.T_world_robot);
  const auto out = [&](const std::string& file) {  // a file of the mode's, recorded
    written_.push_back(name_ + "/" + file);
    return (dir / file).string();
  };
  io::WriteTum(out("trajectory.tum"), trajectory);
  io::WriteG2o(out("graph.g2o"), m.graph().Factors(), m.values());
  const OccupancyGrid grid = ToOccupancyGrid(m);
  const io::MapFilePaths map_files = io::WritePgmMap(out("map.pgm"), grid);
  written_.push_back(name_ + "/" + fs::path(map_files.yaml).filename().string());
  const EntropyResult entropy = ComputeMapEntropy(grid);
  summary.map_entropy_bits = entropy.entropy_bits;
  summary.occupied_share = entropy.occupied_share;

  summary.loop_verification = SummarizeLoops();
  std::optional<Pose2> T_truth_est;
  if (truth) T_truth_est = TruthMetrics(stream, *truth, estimate, grid, &summary);
  summary.present_at = present_at_;
  if (summary.change && T_truth_est) {
    changes_caption_ =
        WriteChangeTiles((dir / "changes.png").string(), *summary.change, grid, *T_truth_est);
    if (!changes_caption_.empty()) {
      changes_png_ = name_ + "/changes.png";
      written_.push_back(changes_png_);
    }
  }
  ScoreReference(stream, trajectory, truth.has_value(), &summary);
  out("loops.csv");
  if (!relations.empty()) {
    const RelationsResult rr = ComputeRelationsError(trajectory, relations);
    summary.relations = RelationsSummary{static_cast<std::int64_t>(rr.count), rr.trans_mean_m,
                                         rr.trans_std_m, rr.rot_mean_deg, rr.rot_std_deg};
  }
  WriteTimelineCsv(out("timeline.csv"), timeline_);
  WriteLoopAttempts(out("loop_attempts.csv"), loop_attempts_);
  if (mode_.Prunes()) {
    WriteMarginalizations(out("marginalizations.csv"), m);
    WriteSparsifications(out("sparsifications.csv"), m);
  }
  const std::vector<std::string> figures = WriteModeFigures(
      config_.out_dir, name_, grid, MakeGraphOverlay(m.graph(), m.values()), T_truth_est, frame);
  *map_png = name_ + "/map.png";
  written_.insert(written_.end(), figures.begin(), figures.end());
  return summary;
}

}  // namespace lifelong::eval
