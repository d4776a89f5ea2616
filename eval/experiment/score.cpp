#include "eval/experiment/score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "eval/metrics/change_recall.hpp"
#include "eval/metrics/trajectory_reference.hpp"
#include "eval/metrics/truth_metrics.hpp"
#include "eval/truth/scan_cells.hpp"
#include "eval/truth/truth_raster.hpp"
#include "eval/truth/world_state.hpp"
#include "io/carmen_log.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"
#include "sim/scenario.hpp"
#include "slam/grid/grid_map.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

// A simulated log's truth files share its stem: LOG.clf(.gz) -> LOG.truth.tum.
std::string SimulatedStem(const std::string& log) {
  std::string stem = log;
  for (const char* ext : {".gz", ".clf", ".log"}) {
    if (stem.size() > std::string(ext).size() &&
        stem.compare(stem.size() - std::string(ext).size(), std::string::npos, ext) == 0) {
      stem.resize(stem.size() - std::string(ext).size());
    }
  }
  return stem;
}

}  // namespace

namespace {

ScoreTruth LoadTruthFiles(const std::string& path) {
  ScoreTruth t;
  t.source = path;
  if (fs::is_directory(path)) {
    const fs::path dir = fs::exists(fs::path(path) / "truth" / "trajectory.tum")
                             ? fs::path(path) / "truth"
                             : fs::path(path);
    t.kind = dir == fs::path(path) ? "truth" : "run";
    if (!fs::exists(dir / "trajectory.tum")) {
      throw InputError(path, 0, "--truth",
                       "neither a run's directory (truth/trajectory.tum) nor a truth directory "
                       "(trajectory.tum)");
    }
    t.trajectory = io::ReadTum((dir / "trajectory.tum").string());
    t.walls = ReadTruthWalls((dir / "").string());
    return t;
  }
  if (!fs::exists(path)) throw InputError(path, 0, "--truth", "no such file or directory");
  const std::string stem = SimulatedStem(path);
  if (fs::exists(stem + ".truth.tum")) {
    t.kind = "simulated log";
    t.trajectory = io::ReadTum(stem + ".truth.tum");
    t.walls = ReadTruthWalls(stem + ".truth.");
    return t;
  }
  const io::CarmenLog log = io::ReadCarmenLog(path);
  if (!log.odometry_recovered || log.corrected_poses.empty()) {
    throw InputError(path, 0, "--truth",
                     "a log without truth: neither a simulated log (no " + stem +
                         ".truth.tum beside it) nor a corrected log (its poses are raw odometry)");
  }
  t.kind = "corrected log";
  t.trajectory = log.corrected_poses;
  t.per_scan = true;
  t.scans = log.observations;
  return t;
}

bool SameSegments(const std::vector<Segment>& a, const std::vector<Segment>& b) {
  const auto near = [](const Segment& p, const Segment& q) {
    return std::abs(p.x0 - q.x0) < 1e-6 && std::abs(p.y0 - q.y0) < 1e-6 &&
           std::abs(p.x1 - q.x1) < 1e-6 && std::abs(p.y1 - q.y1) < 1e-6;
  };
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), near);
}

// The scenario's world, checked against the log's truth files: the surfaces gone by the run's
// end (its last scan; or up to a second later, where the simulation ended) must be those of
// LOG.truth.gone.tsv.
void AddScenarioWorld(const std::string& scenario_path, ScoreTruth* t) {
  if (t->kind != "simulated log") {
    throw InputError(scenario_path, 0, "--scenario",
                     "needs a simulated log as --truth (its scans), not a " + t->kind);
  }
  if (!t->walls) {
    throw InputError(t->source, 0, "--truth",
                     "no " + SimulatedStem(t->source) +
                         ".truth.walls.tsv beside it: --scenario checks its world against it");
  }
  const sim::Scenario scenario = sim::LoadScenario(scenario_path);
  t->stream = io::ReadCarmenLog(t->source).observations;
  if (t->stream.empty() || !std::all_of(t->stream.begin(), t->stream.end(), [](const auto& o) {
        return o.T_world_robot_true.has_value();
      })) {
    throw InputError(t->source, 0, "--truth", "a simulated log whose scans lack TRUEPOS");
  }
  const double last = t->stream.back().stamp_s;
  for (const double end_s : {last, last + 1.0}) {
    const GroundTruth then = TruthOf(scenario.world, end_s);
    if (SameSegments(then.gone, t->walls->gone) && SameSegments(then.walls, t->walls->walls)) {
      t->walls->world = then.world;
      t->walls->end_s = end_s;
      return;
    }
  }
  throw InputError(scenario_path, 0, "--scenario",
                   "its world's walls, doors and boxes at the run's end are not those of " +
                       t->source + "'s truth files: the scenario of another log?");
}

}  // namespace

ScoreTruth LoadScoreTruth(const std::string& path, const std::string& scenario) {
  ScoreTruth t = LoadTruthFiles(path);
  if (!scenario.empty()) AddScenarioWorld(scenario, &t);
  return t;
}

namespace {

// scan_cells of the system on a corrected log: its pose at each scan it covers, against the
// log's own pose of that scan.
void ScoreScanCells(const ScoreTruth& truth, const ScoredSystem& system, ModeSummary* out) {
  if (truth.scans.empty() || truth.scans.size() != truth.trajectory.size()) return;
  // Pairs (log pose, system pose) per scan; pairs.index is the scan's.
  const ReferencePairs pairs = PairScanByScan(truth.trajectory, system.trajectory);
  if (pairs.index.empty()) return;
  const slam::GridMapConfig grid;
  out->scan_cells =
      ScanCells(truth.scans, pairs.index, pairs.reference, grid.resolution_m, grid.max_hit_range_m);
  out->scan_cells_reference =
      ScanCells(truth.scans, pairs.index, pairs.estimate, grid.resolution_m, grid.max_hit_range_m);
}

}  // namespace

SystemScore ScoreSystem(const ScoreTruth& truth, const ScoredSystem& system) {
  const ReferencePairs pairs = truth.per_scan
                                   ? PairScanByScan(system.trajectory, truth.trajectory)
                                   : PairWithReference(system.trajectory, truth.trajectory);
  if (pairs.estimate.empty()) {
    throw InputError(system.name, 0, "--trajectory",
                     "none of its " + std::to_string(system.trajectory.size()) +
                         " poses pairs with the truth's stamps (" +
                         std::to_string(truth.trajectory.size()) + " poses in " + truth.source +
                         "): another run, or another clock?");
  }
  SystemScore out;
  out.summary.reference_matched = static_cast<std::int64_t>(pairs.estimate.size());
  std::optional<GroundTruth> walls = truth.walls;
  const OccupancyGrid* map = system.map ? &*system.map : nullptr;
  if (walls && map) {  // rasterized once, for blur and for stale_seen_cells
    walls->raster = std::make_shared<const TruthRaster>(*walls, pairs.reference, map->resolution_m);
  }
  const Pose2 T = ScoreAgainstTruth(pairs.estimate, pairs.reference, walls ? &*walls : nullptr, map,
                                    &out.summary);
  if (walls && walls->world && map) {
    out.summary.change = ComputeChangeRecall(*walls->world, walls->end_s, truth.stream, *map, T,
                                             SIZE_MAX, walls->raster.get());
  }
  ScoreScanCells(truth, system, &out.summary);
  for (const Pose2& p : pairs.estimate) out.aligned.push_back(T * p);
  out.truth = pairs.reference;
  return out;
}

}  // namespace lifelong::eval
