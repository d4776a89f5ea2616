#include "eval/experiment/score.hpp"

#include <filesystem>

#include "eval/metrics/trajectory_reference.hpp"
#include "eval/metrics/truth_metrics.hpp"
#include "eval/truth/scan_cells.hpp"
#include "eval/truth/world_state.hpp"
#include "io/carmen_log.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"
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

ScoreTruth LoadScoreTruth(const std::string& path) {
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
  const GroundTruth* walls = truth.walls ? &*truth.walls : nullptr;
  const OccupancyGrid* map = system.map ? &*system.map : nullptr;
  const Pose2 T = ScoreAgainstTruth(pairs.estimate, pairs.reference, walls, map, &out.summary);
  ScoreScanCells(truth, system, &out.summary);
  for (const Pose2& p : pairs.estimate) out.aligned.push_back(T * p);
  out.truth = pairs.reference;
  return out;
}

}  // namespace lifelong::eval
