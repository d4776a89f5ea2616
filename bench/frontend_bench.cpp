// Front-end benchmarks: counting grid map updates, information gain (recomputed, and kept by
// the pruned modes' index) and correlative scan matching (incremental and loop-closure
// windows) on the synthetic room of the tests.
#include <benchmark/benchmark.h>

#include "slam/grid/gain_index.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/matching/scan_matcher.hpp"
#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct Scene {
  testing::World room = testing::RoomWorld();
  Pose2 truth{4.2, 2.6, 0.1};
  LaserScan scan = testing::SimulateScan(room, truth);
  std::vector<Pose2> local_poses{
      {1.5, 2.0, 0.0}, {2.5, 2.3, 0.4}, {3.5, 2.0, -0.3}, {3.8, 3.0, 0.2}, {4.0, 2.2, 0.0}};
  std::vector<LaserScan> local_scans;
  Scene() {
    for (const Pose2& p : local_poses) local_scans.push_back(testing::SimulateScan(room, p));
  }
  std::vector<PosedScan> Local() const {
    std::vector<PosedScan> out;
    for (std::size_t i = 0; i < local_poses.size(); ++i) {
      out.push_back({&local_scans[i], local_poses[i]});
    }
    return out;
  }
};

void BM_GridAddRemoveScan(benchmark::State& state) {
  const Scene s;
  GridMap map;
  for (std::size_t i = 0; i < s.local_poses.size(); ++i)
    map.AddScan(s.local_scans[i], s.local_poses[i]);
  for (auto _ : state) {
    map.AddScan(s.scan, s.truth);
    map.RemoveScan(s.scan, s.truth);
  }
  state.counters["beams"] = static_cast<double>(s.scan.ranges_m.size());
  state.counters["cells"] = static_cast<double>(map.TouchedCells(s.scan, s.truth).size());
}
BENCHMARK(BM_GridAddRemoveScan)->Unit(benchmark::kMicrosecond);

void BM_GridTouchedCells(benchmark::State& state) {
  const Scene s;
  const GridMap map;
  for (auto _ : state) benchmark::DoNotOptimize(map.TouchedCells(s.scan, s.truth));
  state.counters["beams"] = static_cast<double>(s.scan.ranges_m.size());
}
BENCHMARK(BM_GridTouchedCells)->Unit(benchmark::kMicrosecond);

void BM_InformationGain(benchmark::State& state) {
  const Scene s;
  GridMap map;
  for (std::size_t i = 0; i < s.local_poses.size(); ++i)
    map.AddScan(s.local_scans[i], s.local_poses[i]);
  map.AddScan(s.scan, s.truth);
  for (auto _ : state) benchmark::DoNotOptimize(map.InformationGain(s.scan, s.truth));
  state.counters["beams"] = static_cast<double>(s.scan.ranges_m.size());
  state.counters["cells"] = static_cast<double>(map.TouchedCells(s.scan, s.truth).size());
}
BENCHMARK(BM_InformationGain)->Unit(benchmark::kMicrosecond);

// The pruned modes' case: the scan's cell list is cached, only the map lookups and entropies
// are timed.
void BM_InformationGainCachedCells(benchmark::State& state) {
  const Scene s;
  GridMap map;
  for (std::size_t i = 0; i < s.local_poses.size(); ++i)
    map.AddScan(s.local_scans[i], s.local_poses[i]);
  const std::vector<CellUpdate> cells = map.TouchedCells(s.scan, s.truth);
  map.Add(cells);
  for (auto _ : state) benchmark::DoNotOptimize(map.InformationGain(cells));
  state.counters["cells"] = static_cast<double>(cells.size());
}
BENCHMARK(BM_InformationGainCachedCells)->Unit(benchmark::kMicrosecond);

// The pruned modes' map change: a scan added to the map and removed again, with the gains of
// the local scans kept exact by the index through both (against recomputing those gains:
// BM_InformationGainCachedCells times one of them).
void BM_GainIndexAddRemoveScan(benchmark::State& state) {
  const Scene s;
  GridMap map;
  GainIndex index;
  std::vector<std::vector<CellUpdate>> local;
  std::vector<CellState> after;
  for (std::size_t i = 0; i < s.local_poses.size(); ++i) {
    local.push_back(map.TouchedCells(s.local_scans[i], s.local_poses[i]));
    map.Add(local.back());
  }
  for (std::size_t i = 0; i < local.size(); ++i) {
    index.Track(static_cast<NodeId>(i), local[i], map.QuantizedGain(local[i]));
  }
  const std::vector<CellUpdate> cells = map.TouchedCells(s.scan, s.truth);
  for (auto _ : state) {
    map.Add(cells, &after);
    index.Apply(cells, after, true);
    map.Remove(cells, &after);
    index.Apply(cells, after, false);
  }
  state.counters["cells"] = static_cast<double>(cells.size());
  state.counters["tracked"] = static_cast<double>(index.size());
}
BENCHMARK(BM_GainIndexAddRemoveScan)->Unit(benchmark::kMicrosecond);

// Tracking a scan (its cells grouped by chunk) and untracking it.
void BM_GainIndexTrackScan(benchmark::State& state) {
  const Scene s;
  GridMap map;
  const std::vector<CellUpdate> cells = map.TouchedCells(s.scan, s.truth);
  map.Add(cells);
  GainIndex index;
  for (auto _ : state) {
    index.Track(0, cells, 0);
    benchmark::DoNotOptimize(index.Untrack(0));
  }
  state.counters["cells"] = static_cast<double>(cells.size());
}
BENCHMARK(BM_GainIndexTrackScan)->Unit(benchmark::kMicrosecond);

void BM_BuildLocalReferenceGrid(benchmark::State& state) {
  const Scene s;
  const MatcherConfig config;
  std::size_t points = 0;
  for (auto _ : state) {
    const std::vector<Eigen::Vector2d> pts = PointsInReference(s.Local(), 0.03);
    points = pts.size();
    const ReferenceGrid grid(pts, config);
    grid.PrepareAllBounds();  // every level on every tile: a search builds only what it reads
    benchmark::DoNotOptimize(grid.width());
  }
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_BuildLocalReferenceGrid)->Unit(benchmark::kMicrosecond);

// The mapper's case: one table rebuilt in place for every scan (its memory reused).
void BM_RebuildLocalReferenceGrid(benchmark::State& state) {
  const Scene s;
  const MatcherConfig config;
  ReferenceGrid grid;
  std::size_t points = 0;
  for (auto _ : state) {
    const std::vector<Eigen::Vector2d> pts = PointsInReference(s.Local(), 0.03);
    points = pts.size();
    grid.Build(pts, config);
    grid.PrepareAllBounds();
    benchmark::DoNotOptimize(grid.width());
  }
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_RebuildLocalReferenceGrid)->Unit(benchmark::kMicrosecond);

// Times matching the scene's scan, thinned at `spacing_m`, against `ref`.
void RunMatch(benchmark::State& state, const ReferenceGrid& ref, const Scene& s, const Pose2& guess,
              const MatcherConfig& config, double spacing_m = 0.03) {
  const std::vector<Eigen::Vector2d> pts = ScanToPoints(s.scan, spacing_m);
  MatchResult r;
  for (auto _ : state) r = Match(ref, pts, guess, config);
  state.counters["beams"] = static_cast<double>(s.scan.ranges_m.size());
  state.counters["points"] = static_cast<double>(pts.size());
  state.counters["evaluations"] = r.evaluations;
  state.counters["bounds"] = r.bound_evaluations;
  state.counters["error_cm"] =
      100.0 * std::hypot(r.T_ref_cur.x - s.truth.x, r.T_ref_cur.y - s.truth.y);
}

// Incremental: +-0.3 m, +-15 deg against a local map of five recent scans.
void BM_MatchIncremental(benchmark::State& state) {
  const Scene s;
  MatcherConfig config;
  config.linear_window_m = 0.3;
  config.angular_window_rad = 15.0 * kDeg;
  const ReferenceGrid ref(PointsInReference(s.Local(), 0.03), config);
  RunMatch(state, ref, s, s.truth * Pose2(0.12, -0.08, 5.0 * kDeg), config);
}
BENCHMARK(BM_MatchIncremental)->Unit(benchmark::kMillisecond);

// The mapper's incremental case with its defaults (configs/default.yaml): the local map is
// the recent scans' surfaces (returns joined along lines, SurfacePoints) sampled at the
// 0.05 m thinning spacing, the scan's points thinned likewise, and the off-lattice
// refinement on.
void BM_MatchIncrementalSurfaces(benchmark::State& state) {
  const Scene s;
  MatcherConfig config;
  config.linear_window_m = 0.3;
  config.angular_window_rad = 0.26;
  config.resolution_m = 0.03;
  config.sigma_m = 0.05;
  config.refine = true;
  std::vector<Eigen::Vector2d> reference;
  for (const PosedScan& local : s.Local()) {
    for (const Eigen::Vector2d& p : SurfacePoints(*local.scan, 0.05, SurfaceRule{})) {
      Eigen::Vector2d q;
      local.T_ref_robot.Apply(p.x(), p.y(), &q.x(), &q.y());
      reference.push_back(q);
    }
  }
  const ReferenceGrid ref(reference, config);
  RunMatch(state, ref, s, s.truth * Pose2(0.12, -0.08, 5.0 * kDeg), config, 0.05);
  state.counters["reference"] = static_cast<double>(reference.size());
}
BENCHMARK(BM_MatchIncrementalSurfaces)->Unit(benchmark::kMillisecond);

// Loop closure: +-2 m, +-30 deg against one older node's scan; argument: coarse factor.
void BM_MatchLoopClosure(benchmark::State& state) {
  const Scene s;
  MatcherConfig config;
  config.coarse_factor = static_cast<int>(state.range(0));
  config.linear_window_m = 2.0;
  config.angular_window_rad = 30.0 * kDeg;
  const ReferenceGrid ref(PointsInReference({s.Local()[1]}, 0.03), config);
  RunMatch(state, ref, s, s.truth * Pose2(1.1, -0.7, 20.0 * kDeg), config);
}
BENCHMARK(BM_MatchLoopClosure)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);

// A refused loop search, the common case on a long log: the room's scan against an older
// node's, guessed 3 m off, so that the true pose lies outside the +-2 m window and the best
// inside it overlaps only in part; at the loop closer's min_score (0.6). Argument 1: the
// search stops at min_score (MatcherConfig::cut_below_min_score, the loop closer's default),
// 0: it searches on to the best pose.
void BM_MatchLoopClosureRefused(benchmark::State& state) {
  const Scene s;
  MatcherConfig config;
  config.linear_window_m = 2.0;
  config.angular_window_rad = 30.0 * kDeg;
  config.min_score = 0.6;
  config.cut_below_min_score = state.range(0) != 0;
  const ReferenceGrid ref(PointsInReference({s.Local()[1]}, 0.03), config);
  RunMatch(state, ref, s, s.truth * Pose2(3.0, -0.7, 20.0 * kDeg), config);
}
BENCHMARK(BM_MatchLoopClosureRefused)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lifelong::slam
