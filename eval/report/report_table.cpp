#include "eval/report/report_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>

#include <nlohmann/json.hpp>

#include "eval/common/html.hpp"
#include "eval/common/mode_order.hpp"
#include "eval/figures/mode_colors.hpp"

namespace lifelong::eval {
namespace {

using nlohmann::json;

constexpr double kKiB = 1.0 / 1024.0;
constexpr double kSecondsPerMs = 1e-3;

const char kRuntime[] = "Runtime";
const char kGraph[] = "Graph and memory";
const char kAccuracy[] = "Accuracy";
const char kMap[] = "Map quality";

/// Every mode's object of summary.json, by name: the rows' pointers read it.
json ModesJson(const RunSummary& summary) {
  json all = json::object();
  for (const auto& [name, mode] : summary.modes) all[name] = ModeSummaryJson(mode);
  return all;
}

/// The value of a row for a mode, scaled; absent when the mode has no such figure.
std::optional<double> Value(const json& mode, const TableRow& row, bool* is_integer) {
  const json::json_pointer ptr(row.pointer);
  if (!mode.contains(ptr) || !mode.at(ptr).is_number()) return std::nullopt;
  const json& v = mode.at(ptr);
  *is_integer = v.is_number_integer() && row.scale == 1.0;
  return v.get<double>() * row.scale;
}

/// The smallest baseline a ratio is taken against: a time under a millisecond is noise
/// (e.g. "82x" of 35 us of bookkeeping); other figures need only a non-zero baseline.
double RatioFloor(const TableRow& row) {
  const std::string unit = row.unit;
  if (unit == "s") return 1e-3;
  if (unit == "ms") return 1.0;
  return 0.0;
}

/// What a row's cell of one mode shows beyond the bare value.
struct CellContext {
  std::optional<double> base;                     ///< the baseline's value; none: no ratio
  std::optional<std::int64_t> relations_in_file;  ///< summary.json's log.relations_in_file
};

std::string Cell(const json& mode, const TableRow& row, const CellContext& context) {
  const std::string pointer = row.pointer;
  bool is_integer = false;
  const std::optional<double> v = Value(mode, row, &is_integer);
  if (!v) {
    // Precision is undefined without an accepted closure: say so rather than a dash.
    const json::json_pointer accepted("/loop_verification/accepted");
    if (pointer == "/loop_precision" && mode.contains(accepted) && mode.at(accepted) == 0)
      return "<td class=\"na\">no closures</td>";
    return "<td class=\"na\">&ndash;</td>";
  }
  // A stage that never ran during the observations: 0 s would read as "free".
  if (pointer.rfind("/stage_ms/", 0) == 0 && *v == 0.0) return "<td class=\"na\">not run</td>";
  if (pointer == "/relations/count" && context.relations_in_file) {
    const bool few = *v * 2.0 < static_cast<double>(*context.relations_in_file);
    return std::string(few ? "<td class=\"warn\">" : "<td>") + FormatValue(*v, true) + " of " +
           std::to_string(*context.relations_in_file) + "</td>";
  }
  std::string html = "<td>" + FormatValue(*v, is_integer);
  const std::optional<double>& base = context.base;
  if (row.ratio && base && *base != 0.0 && std::fabs(*base) >= RatioFloor(row)) {
    html += " <span class=\"ratio\">" + FormatRatio(*v / *base) + "</span>";
  }
  return html + "</td>";
}

/// The table's header row: figure, unit, one column per mode (and the definitions).
std::string HeadHtml(const std::vector<std::string>& modes, bool definitions) {
  std::string head = "<tr><th>figure</th><th>unit</th>";
  for (const std::string& m : modes) {
    head += "<th><span class=\"swatch\" style=\"background:" + ModeColourHex(m) + "\"></span>" +
            HtmlEscape(m) + "</th>";
  }
  return head + (definitions ? "<th>definition</th></tr>\n" : "</tr>\n");
}

/// One row's <tr>; "" when no mode has the figure.
std::string RowHtml(const TableRow& row, const std::vector<std::string>& modes, const json& all,
                    const RunSummary& summary, bool definitions) {
  bool any = false, is_integer = false;
  for (const std::string& m : modes) any = any || Value(all.at(m), row, &is_integer).has_value();
  if (!any) return "";
  const std::optional<double> base = Value(all.at(modes.front()), row, &is_integer);
  std::string html = definitions ? "<tr><td>" + std::string(row.label) + "</td>"
                                 : "<tr><td title=\"" + HtmlEscape(row.definition) + "\">" +
                                       std::string(row.label) + "</td>";
  html += "<td class=\"unit\">" + std::string(row.unit) + "</td>";
  CellContext context;
  if (summary.log) context.relations_in_file = summary.log->relations_in_file;
  for (const std::string& m : modes) {
    context.base = m == modes.front() ? std::nullopt : base;
    html += Cell(all.at(m), row, context);
  }
  if (definitions) html += "<td class=\"def\">" + HtmlEscape(row.definition) + "</td>";
  return html + "</tr>\n";
}

}  // namespace

// Every row, in the table's order (data table).
const std::vector<TableRow>& SummaryTableRows() {
  static const std::vector<TableRow> rows = {
      {kRuntime, "/observations", "observations", "", 1, false,
       "scans taken as graph nodes (the robot moved or turned enough since the last one)"},
      {kRuntime, "/wall_time_s", "mapper time", "s", 1, true,
       "time spent in the mapper over the whole stream, the final optimization included"},
      {kRuntime, "/time_per_obs_ms/mean", "time per observation, mean", "ms", 1, true,
       "mapper time per observation, mean over all observations (seed Figs. 6.1-6.4)"},
      {kRuntime, "/time_per_obs_ms/p50", "time per observation, median", "ms", 1, true,
       "50th percentile of the time per observation"},
      {kRuntime, "/time_per_obs_ms/p95", "time per observation, 95th percentile", "ms", 1, true,
       "95th percentile of the time per observation"},
      {kRuntime, "/time_per_obs_ms/max", "time per observation, maximum", "ms", 1, true,
       "the slowest observation"},
      {kRuntime, "/time_per_obs_ms/first_pass_mean", "time per observation, first pass", "ms", 1,
       true, "mean over the first pass (first forth-and-back cycle, or every tour place once)"},
      {kRuntime, "/time_per_obs_ms/last10_mean", "time per observation, last 10 %", "ms", 1, true,
       "mean over the last tenth of the observations: the cost once the area is mapped"},
      {kRuntime, "/stage_ms/matching", "time in matching", "s", kSecondsPerMs, true,
       "incremental scan matching and insertion of the new scan into the map"},
      {kRuntime, "/stage_ms/loop_closing", "time in loop closing", "s", kSecondsPerMs, true,
       "candidates, loop-closure matching, uniqueness and group verification"},
      {kRuntime, "/stage_ms/optimization", "time in optimization", "s", kSecondsPerMs, true,
       "the back-end (sparse least squares) alone"},
      {kRuntime, "/stage_ms/map_update", "time in map update", "s", kSecondsPerMs, true,
       "re-rendering scans whose nodes an optimization moved"},
      {kRuntime, "/stage_ms/gains", "time in information gains", "s", kSecondsPerMs, true,
       "information gain of the neighbourhood scans (pruned modes)"},
      {kRuntime, "/stage_ms/marginalization", "time in removal and sparsification", "s",
       kSecondsPerMs, true, "marginalizing nodes out and keeping the edge budget"},
      {kRuntime, "/stage_ms/other", "time in other", "s", kSecondsPerMs, true,
       "bookkeeping: the mapper time not in a stage above"},
      {kGraph, "/nodes_final", "nodes, final", "", 1, true, "graph nodes at the end"},
      {kGraph, "/nodes_max", "nodes, maximum", "", 1, true, "most graph nodes at any time"},
      {kGraph, "/nodes_after_first_pass", "nodes after the first pass", "", 1, true,
       "graph nodes when the first pass ended: the size of the mapped area in nodes"},
      {kGraph, "/edges_final", "edges, final", "", 1, true,
       "graph edges at the end; a dense clique over m nodes counts m(m-1)/2"},
      {kGraph, "/edges_max", "edges, maximum", "", 1, true, "most graph edges at any time"},
      {kGraph, "/edges_by_kind/odometry", "odometry edges", "", 1, false,
       "final factors from incremental scan matching"},
      {kGraph, "/edges_by_kind/loop", "loop-closure edges", "", 1, false,
       "final factors from accepted loop closures"},
      {kGraph, "/edges_by_kind/marginal", "marginal edges", "", 1, false,
       "final factors made by marginalizing nodes out (Chow-Liu tree or naive composition)"},
      {kGraph, "/edges_by_kind/clique_pairs", "exact-clique pairs", "", 1, false,
       "node pairs of the dense clique factors left by exact marginalization"},
      {kGraph, "/edges_by_kind/prior", "prior edges", "", 1, false, "final unary-like factors"},
      {kGraph, "/gamma_final", "gamma index, final", "", 1, false,
       "e / (v(v-1)/2): 0 for no edges, 1 for a complete graph (seed eq. 6.1)"},
      {kGraph, "/scans_kept_pct", "scans kept", "%", 1, false,
       "final nodes as a share of the observations"},
      {kGraph, "/peak_rss_mb", "peak resident memory", "MiB", 1, true,
       "the process's peak RSS while this mode ran, the observation stream included"},
      {kGraph, "/graph_bytes_final", "graph memory, final", "KiB", kKiB, true,
       "bytes held by the graph's nodes, edges and cliques at the end"},
      {kAccuracy, "/ate_rmse_m", "ATE RMSE", "cm", 100, true,
       "RMS position error of every scan's pose after the best rigid alignment to the truth "
       "(or to the log's reference trajectory)"},
      {kAccuracy, "/rpe_1m/trans_rmse_m", "RPE over 1 m, translation", "cm", 100, true,
       "RMS translation error of the motion between poses 1 m apart along the truth or reference"},
      {kAccuracy, "/rpe_1m/rot_rmse_deg", "RPE over 1 m, rotation", "deg", 1, true,
       "RMS heading error of the motion between poses 1 m apart along the truth or reference"},
      {kAccuracy, "/rpe_1m/count", "RPE pairs", "", 1, false,
       "pose pairs 1 m apart along the truth or reference that the RPE is taken over"},
      {kAccuracy, "/reference_matched", "poses scored against the reference", "", 1, false,
       "estimate poses with a reference pose at their stamp (or scan); the rest are left out"},
      {kAccuracy, "/sequential/count", "observations after the first", "", 1, false,
       "observations that were matched against the local map of recent scans"},
      {kAccuracy, "/sequential/matched", "observations matched to the local map", "", 1, false,
       "of those, the ones whose match was good; the rest kept odometry alone"},
      {kAccuracy, "/sequential/degenerate", "matches ambiguous along a direction", "", 1, false,
       "of the matched, those whose position along a corridor-like direction came from odometry"},
      {kAccuracy, "/sequential/weak", "weak matches refused", "", 1, false,
       "not matched: scored under incremental.weak_score with a rival too close; odometry kept"},
      {kAccuracy, "/sequential/recovered", "matches found by the wider search", "", 1, false,
       "of the matched, those found only by the second search over incremental.recovery_window_m "
       "(the odometry step was further off than the matcher's window)"},
      {kAccuracy, "/sequential/lost", "steps whose odometry the log lost", "", 1, false,
       "searched over a full turn and incremental.lost_window_m (matched ones count above)"},
      {kAccuracy, "/loop_precision", "loop-closure precision", "%", 100, false,
       "share of accepted loop closures within 0.3 m and 5 deg of the true relative pose (a log: "
       "of its reference's)"},
      {kAccuracy, "/loop_recall", "loop-closure recall", "%", 100, false,
       "share of revisits (1 m, 30 deg of an older node) with a correct loop closure"},
      {kAccuracy, "/loop_precision_last_hour", "loop-closure precision, last hour", "%", 100, false,
       "precision of the closures accepted in the run's last hour (runs over an hour)"},
      {kAccuracy, "/loop_verification/attempts", "loop-closing attempts", "", 1, false,
       "observations with a loop-closure candidate inside the gate; each ends in one of the "
       "five refusals below or in a proposed closure"},
      {kAccuracy, "/loop_verification/few_points", "submaps with too few points", "", 1, false,
       "attempts whose submap had fewer points within the search's reach than the minimum"},
      {kAccuracy, "/loop_verification/low_score", "matches scoring too low", "", 1, false,
       "attempts whose best match scored below the minimum"},
      {kAccuracy, "/loop_verification/ambiguous", "matches ambiguous", "", 1, false,
       "attempts whose best match had a close second more than 0.5 m or 0.2 rad away"},
      {kAccuracy, "/loop_verification/not_unique", "matches not locally unique", "", 1, false,
       "loop-closure matches refused before verification: a pose 0.25 m away scores alike"},
      {kAccuracy, "/loop_verification/implausible", "matches implausible", "", 1, false,
       "attempts whose correction lay outside the gate of the projected uncertainty"},
      {kAccuracy, "/loop_verification/proposed", "closures proposed", "", 1, false,
       "loop-closure hypotheses from the matcher, before group verification"},
      {kAccuracy, "/loop_verification/accepted", "closures accepted", "", 1, false,
       "hypotheses confirmed by a mutually consistent group and put into the graph"},
      {kAccuracy, "/loop_verification/rejected", "closures rejected", "", 1, false,
       "hypotheses inconsistent with every accepted closure around them"},
      {kAccuracy, "/loop_verification/expired", "closures expired", "", 1, false,
       "hypotheses never confirmed within loops.verify.expiry_m of travel"},
      {kAccuracy, "/loop_verification/injected", "false closures injected", "", 1, false,
       "wrong closures injected on purpose (false_closures.share)"},
      {kAccuracy, "/loop_verification/injected_accepted", "false closures accepted", "", 1, false,
       "injected wrong closures that verification let into the graph"},
      {kAccuracy, "/relations/count", "relations used", "", 1, false,
       "relations of the --relations file whose two stamps fall on scans of the log"},
      {kAccuracy, "/relations/trans_mean_m", "relation error, translation, mean", "m", 1, true,
       "Kümmerle et al. 2009: translation of the estimated vs the true relative pose, mean"},
      {kAccuracy, "/relations/trans_std_m", "relation error, translation, std", "m", 1, true,
       "standard deviation of the translational relation error"},
      {kAccuracy, "/relations/rot_mean_deg", "relation error, rotation, mean", "deg", 1, true,
       "rotation of the estimated vs the true relative pose, mean"},
      {kAccuracy, "/relations/rot_std_deg", "relation error, rotation, std", "deg", 1, true,
       "standard deviation of the rotational relation error"},
      {kAccuracy, "/kld/count", "marginalizations", "", 1, false,
       "nodes marginalized out (rows of marginalizations.csv)"},
      {kAccuracy, "/kld/mean", "KL divergence, mean", "nats", 1, false,
       "KL divergence of each approximate clique from the exact marginal, mean (0: exact)"},
      {kAccuracy, "/kld/max", "KL divergence, maximum", "nats", 1, false,
       "the largest KL divergence of one marginalization"},
      {kAccuracy, "/kld/infinite", "KL divergence infinite", "", 1, false,
       "marginalizations whose approximation lost an informative direction outright (mean and "
       "maximum are then infinite)"},
      {kAccuracy, "/kld/mean_finite", "KL divergence, mean of the finite", "nats", 1, false,
       "the mean over the other marginalizations"},
      {kMap, "/blur/mean_cm", "blur, mean", "cm", 1, true,
       "distance of the aligned map's occupied cells (p >= 0.65) to the nearest true wall"},
      {kMap, "/blur/p95_cm", "blur, 95th percentile", "cm", 1, true,
       "95th percentile of that distance"},
      {kMap, "/blur/thickness", "wall thickness", "cells/m", 1, true,
       "occupied cells per metre of true wall (thick, blurred walls score high)"},
      {kMap, "/blur/recall", "wall recall", "%", 100, false,
       "true-wall cells within 8 m of the path with an occupied cell within 1.5 cells"},
      {kMap, "/current_blur/mean_cm", "blur of the present, mean", "cm", 1, true,
       "as blur, against the walls, doors and boxes as they stand at the run's end (a "
       "changing world only)"},
      {kMap, "/current_recall", "wall recall of the present", "%", 100, false,
       "as wall recall, against the surfaces standing at the run's end"},
      {kMap, "/change_recall", "changes shown", "%", 100, false,
       "doors and boxes that changed during the run and were seen in its last 10 minutes, "
       "whose final map shows them as they stand at the end"},
      {kMap, "/stale_cells", "stale cells", "%", 100, true,
       "occupied cells showing a door or box that is gone by the run's end (within 1.5 "
       "cells of it and of nothing standing then)"},
      {kMap, "/stale_seen_cells", "stale cells seen gone", "%", 100, true,
       "stale cells on a place the robot saw empty after the door or box last changed (a "
       "beam crossed it): those a map could have cleared"},
      {kMap, "/map_entropy_bits", "map entropy", "bits", 1, true,
       "sum of the binary entropy H(p) over the known cells (seed eq. 5.8)"},
      {kMap, "/occupied_share", "occupied share", "%", 100, false, "known cells with p >= 0.65"},
      {kMap, "/scan_cells", "scan cells", "", 1, true,
       "grid cells the scans' returns fall in at the mode's poses (fewer: sharper); the "
       "scans the truth or reference has a pose for"},
      {kMap, "/scan_cells_reference", "scan cells at the reference", "", 1, true,
       "the same scans at the truth's or the reference's poses: a reference that is another "
       "system's estimate can be less sharp than the mode"},
  };
  return rows;
}

std::string FormatValue(double value, bool is_integer) {
  char buf[64];
  if (is_integer || std::fabs(value) >= 1000.0) {
    std::snprintf(buf, sizeof(buf), "%.0f", value);
  } else {
    std::snprintf(buf, sizeof(buf), "%.3g", value);
  }
  return buf;
}

std::string FormatRatio(double ratio) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), ratio >= 100.0 ? "%.0f" : "%.2g", ratio);
  return std::string(buf) + "\u00d7";
}

std::vector<std::string> OrderedModes(const RunSummary& summary) {
  return ModesInOrder(summary.modes, summary.mode_order);
}

std::string SummaryTableHtml(const RunSummary& summary) {
  const std::vector<std::string> modes = OrderedModes(summary);
  if (modes.empty()) return "";
  const json all = ModesJson(summary);
  std::string body;
  const char* group = "";
  const std::size_t columns = modes.size() + 3;
  for (const TableRow& row : SummaryTableRows()) {
    const std::string tr = RowHtml(row, modes, all, summary, true);
    if (tr.empty()) continue;  // a row no mode has: left out
    if (std::string(group) != row.group) {
      group = row.group;
      body += "<tr class=\"group\"><th colspan=\"" + std::to_string(columns) + "\">" +
              std::string(group) + "</th></tr>\n";
    }
    body += tr;
  }
  const std::string note =
      "<p class=\"note\">Grey &times; figures: the mode's value divided by the baseline's, <b>" +
      HtmlEscape(modes.front()) +
      "</b> (the first mode of <code>--modes</code>), where a ratio means something (not "
      "against a time under 1 ms). &ndash; : the figure does not apply to that mode; "
      "<i>not run</i>: the stage never ran during the observations (the final optimization "
      "after the last one counts in the mapper time only).</p>\n";
  return "<table class=\"summary\">\n" + HeadHtml(modes, true) + body + "</table>\n" + note;
}

const std::vector<std::string>& KeyFigurePointers() {
  static const std::vector<std::string> pointers = {
      "/time_per_obs_ms/mean", "/time_per_obs_ms/last10_mean",
      "/wall_time_s",          "/nodes_final",
      "/edges_final",          "/scans_kept_pct",
      "/ate_rmse_m",           "/blur/mean_cm",
      "/loop_precision",       "/loop_recall",
      "/relations/count",      "/relations/trans_mean_m",
      "/peak_rss_mb"};
  return pointers;
}

std::string KeyTableHtml(const RunSummary& summary) {
  const std::vector<std::string> modes = OrderedModes(summary);
  if (modes.empty()) return "";
  const json all = ModesJson(summary);
  std::string body;
  for (const std::string& pointer : KeyFigurePointers()) {
    for (const TableRow& row : SummaryTableRows()) {
      if (row.pointer == pointer) body += RowHtml(row, modes, all, summary, false);
    }
  }
  return "<table class=\"summary key\">\n" + HeadHtml(modes, false) + body + "</table>\n";
}

}  // namespace lifelong::eval
