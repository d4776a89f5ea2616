// The output contract of DESIGN.md: summary.json and <mode>/timeline.csv (report.html:
// eval/report/report_html.hpp).
// Every writer goes through io::WriteFileAtomically, so a file that exists is whole.
// A figure that does not apply is an empty std::optional and is absent from the JSON.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "eval/metrics/change_recall.hpp"
#include "eval/metrics/types.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/loops/loop_verifier.hpp"

namespace lifelong::eval {

/// Time per observation, ms. first_pass_mean: observations with obs < first_pass_end_obs;
/// last10_mean: the last ceil(10%) of the observations.
struct TimeStats {
  double mean = 0.0, p50 = 0.0, p95 = 0.0, max = 0.0;
  std::optional<double> first_pass_mean;
  double last10_mean = 0.0;
};

struct BlurSummary {
  /// Absent when the map has no occupied cell: no distance to a wall was measured, and 0
  /// would read as a perfect map.
  std::optional<double> mean_cm, p95_cm;
  double thickness = 0.0;
  std::optional<double> recall;  ///< absent when no true wall was visible
};
struct RelationsSummary {
  std::int64_t count = 0;
  double trans_mean_m = 0.0, trans_std_m = 0.0, rot_mean_deg = 0.0, rot_std_deg = 0.0;
};
/// Loop-closure verification counts (slam/loops/loop_verifier.hpp); summary.json's
/// "loop_verification".
struct LoopVerificationSummary {
  slam::LoopVerifierStats counts;
  bool injection = false;  ///< the false-closure test was on; else injected* are not written
  bool global = false;     ///< the global search was on; else global_* are not written
  /// Accepted closures whose edge, still in the graph at the end, has a chi2 above
  /// loops.suspect_chi2: the back-end's kernel is switching them off.
  std::int64_t switched_off = 0;
};
/// RPE over 1 m of travelled reference path (eval/metrics/trajectory_reference.hpp); summary.json's
/// "rpe_1m".
struct RpeSummary {
  std::int64_t count = 0;
  double trans_rmse_m = 0.0, rot_rmse_deg = 0.0;
};
/// Sequential scan matching (each observation against the local map of recent scans):
/// summary.json's "sequential". An observation that did not match keeps its odometry.
struct SequentialSummary {
  std::int64_t count = 0;    ///< observations after the first
  std::int64_t matched = 0;  ///< of those, matched (the rest keep odometry alone)
  /// of the matched, ambiguous along one direction, which their odometry measured
  std::int64_t degenerate = 0;
  /// not matched: weak and not distinct from a rival, so they kept their odometry
  std::int64_t weak = 0;
  /// of the matched, found by the wider second search (incremental.recovery_window_m)
  std::int64_t recovered = 0;
  /// whose odometry the stream lost (searched over a full turn; counted in matched if found)
  std::int64_t lost = 0;
};
struct KldSummary {
  std::int64_t count = 0;
  double mean = 0.0, max = 0.0;  ///< +inf (null in JSON) when any removal's KL is infinite
  std::int64_t infinite = 0;     ///< removals whose approximation lost a direction outright
  double mean_finite = 0.0;      ///< mean over the others (0 when there are none)
};

/// The map of the present at a time the user asked for (`run --present-at`): the figures
/// the end has (current_blur, current_recall, stale_cells, change_recall), against the world
/// as it stood at t_s, of the map and trajectory as they were at the first scan at or after
/// it.
struct PresentAt {
  double t_s = 0.0;
  std::optional<double> ate_rmse_m;
  std::optional<BlurSummary> current_blur;
  std::optional<double> stale_cells;
  std::optional<double> stale_seen_cells;
  std::optional<double> change_recall;
  std::optional<std::int64_t> change_recall_seen;
};

/// One entry of "modes" in summary.json; the names match the JSON keys.
struct ModeSummary {
  std::optional<std::int64_t> observations;
  std::optional<double> wall_time_s;
  std::optional<TimeStats> time_per_obs_ms;
  std::optional<std::int64_t> nodes_final, edges_final, nodes_max, edges_max;
  std::optional<std::int64_t> nodes_after_first_pass;
  /// Final graph's factors by origin: "odometry", "loop", "marginal" (Chow-Liu or naive
  /// edges), "prior", and "clique_pairs" (pairs of exact clique factors, as for gamma).
  std::map<std::string, std::int64_t> edges_by_kind;
  std::optional<SequentialSummary> sequential;
  std::optional<double> gamma_final;
  std::optional<double> scans_kept_pct;
  std::optional<double> peak_rss_mb;
  std::optional<std::int64_t> graph_bytes_final;
  std::optional<BlurSummary> blur;  ///< ground truth only
  /// Against the world as it stands at the run's end (issue #35), when it changed during the
  /// run: blur and recall of the present, and the share of occupied cells showing a surface
  /// gone by then.
  std::optional<BlurSummary> current_blur;
  std::optional<double> stale_cells;
  /// Per door or box that changed during the run: whether the map shows its state at the
  /// end (eval/metrics/change_recall.hpp); simulated runs only.
  std::optional<ChangeRecall> change;
  std::vector<PresentAt> present_at;  ///< run --present-at, in time order
  std::optional<double> ate_rmse_m;   ///< ground truth or a reference trajectory
  std::optional<RpeSummary> rpe_1m;   ///< ground truth or a reference trajectory
  /// Reference trajectory: estimate poses scored against it (others had no reference pose).
  std::optional<std::int64_t> reference_matched;
  std::optional<double> loop_precision;  ///< ground truth only, >= 1 closure accepted
  std::optional<double> loop_recall;     ///< ground truth only, >= 1 revisit
  /// Ground truth, runs over an hour: precision of the closures accepted in the last hour.
  std::optional<double> loop_precision_last_hour;
  std::optional<LoopVerificationSummary> loop_verification;
  std::optional<RelationsSummary> relations;  ///< with --relations
  std::optional<KldSummary> kld;              ///< marginalizing modes
  /// Mapper time by stage over the run, ms: matching, loop_closing, optimization,
  /// map_update, gains, marginalization, other (bookkeeping: time_ms minus the rest).
  std::map<std::string, double> stage_ms;
  std::optional<double> map_entropy_bits;
  std::optional<double> occupied_share;
  /// The run's scans drawn at this mode's poses and at the reference's (the truth, or a log's
  /// reference), over the scans both have: the distinct grid cells their returns fall in
  /// (eval/truth/scan_cells.hpp). Fewer is sharper.
  std::optional<std::int64_t> scan_cells;
  std::optional<std::int64_t> scan_cells_reference;
};

/// What was read from a real log (replay only): summary.json's "log" object.
struct LogInfo {
  std::int64_t scans = 0;
  std::int64_t backward_stamps = 0;  ///< scans stamped earlier than the scan before them
  /// Distinct stamps among the scans: fewer than `scans` means the trajectory files, which
  /// carry the log's stamps, pair with the reference by line, not by time.
  std::int64_t distinct_stamps = 0;
  std::int64_t odometry_lost = 0;            ///< scans with no odometry of their own (Observation)
  std::optional<double> relations_offset_s;  ///< s, relation time = log time + this
  std::optional<bool> relations_offset_detected;  ///< false: given with --relations-offset
  std::optional<std::int64_t> relations_in_file;  ///< relations read from the file
  /// The reference trajectory ATE and RPE are scored against: a file given with --reference,
  /// or "corrected FLASER poses" of a GMapping-corrected log.
  std::optional<std::string> reference;
  std::optional<std::int64_t> reference_poses;
  /// replay --seed: the seed of the draw replayed (eval/experiment/log_draw.hpp); absent:
  /// the log as recorded.
  std::optional<std::int64_t> draw_seed;
};

/// What happened in the simulator (run only): summary.json's "simulation" object. A run
/// whose robot collided (unless the scenario expects it) or whose route timed out did not
/// drive the scenario it names: `run` exits 1 and a sweep keeps it out of its aggregate.
struct SimulationOutcome {
  bool collided = false;
  bool timed_out = false;
  bool collisions_expected = false;  ///< the scenario's collisions_expected
  std::int64_t collisions = 0;
  std::optional<double> first_collision_s;          ///< s, simulated time
  std::optional<std::string> first_collision_with;  ///< wall, door or box name
  double duration_s = 0.0;                          ///< s, simulated
  double expected_duration_s = 0.0;                 ///< s, the route's estimate
  bool Failed() const { return timed_out || (collided && !collisions_expected); }
};

struct RunSummary {
  std::string source;                           ///< scenario or log path
  std::optional<std::int64_t> seed;             ///< simulation only
  double wall_time_s = 0.0;                     ///< s, whole command
  std::optional<double> log_duration_s;         ///< s, simulated or recorded time covered (>= 0)
  std::optional<LogInfo> log;                   ///< replay only
  std::optional<SimulationOutcome> simulation;  ///< run only
  std::map<std::string, ModeSummary> modes;
  /// The modes in --modes order; the first is the baseline that ratios are taken against.
  std::vector<std::string> mode_order;
};

/// The graph's factors counted by origin (ModeSummary::edges_by_kind); kinds with no factor
/// are left out.
std::map<std::string, std::int64_t> EdgesByKind(const slam::PoseGraph& graph);

/// Time statistics of a timeline; empty optional for an empty timeline.
/// first_pass_end_obs: observations with obs < this form the first pass (absent: none).
std::optional<TimeStats> ComputeTimeStats(const std::vector<TimelineRow>& rows,
                                          std::optional<int> first_pass_end_obs);

/// Fills observations, time_per_obs_ms, nodes/edges final and max, nodes_after_first_pass
/// (nodes at the last row with obs < first_pass_end_obs), gamma_final, graph_bytes_final,
/// and peak_rss_mb (max rss_mb of the rows; overwrite it with PeakRssMb() if preferred).
ModeSummary SummarizeTimeline(const std::vector<TimelineRow>& rows,
                              std::optional<int> first_pass_end_obs);

/// Mapper time by stage summed over a timeline (ModeSummary::stage_ms).
std::map<std::string, double> StageTotals(const std::vector<TimelineRow>& rows);

/// KL statistics over the divergences of a mode's marginalizations; absent when empty.
std::optional<KldSummary> SummarizeKld(const std::vector<double>& kl_values);

/// A mode's object of summary.json (docs/output-contract.md). Never holds NaN: a non-finite
/// figure is absent.
nlohmann::json ModeSummaryJson(const ModeSummary& mode);

/// The summary as JSON text (2-space indent). Never writes NaN: non-finite becomes absent.
std::string SummaryJsonText(const RunSummary& summary);

/// Writes summary.json atomically. Throws std::runtime_error naming the path on failure.
void WriteSummaryJson(const std::string& path, const RunSummary& summary);

/// Writes the timeline CSV with header obs,t_s,time_ms,nodes,edges,gamma,rss_mb,
/// graph_bytes,loop_closures. Throws std::runtime_error naming the path on failure.
void WriteTimelineCsv(const std::string& path, const std::vector<TimelineRow>& rows);

}  // namespace lifelong::eval
