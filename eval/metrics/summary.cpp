#include "eval/metrics/summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "eval/metrics/metrics.hpp"
#include "io/atomic_file.hpp"

namespace lifelong::eval {
namespace {

using nlohmann::json;

double Mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

template <typename T>
void Put(json& j, const char* key, const std::optional<T>& v) {
  if (!v) return;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(*v)) return;
  }
  j[key] = *v;
}

json TimeJson(const TimeStats& t) {
  json j = {{"mean", t.mean},
            {"p50", t.p50},
            {"p95", t.p95},
            {"max", t.max},
            {"last10_mean", t.last10_mean}};
  Put(j, "first_pass_mean", t.first_pass_mean);
  return j;
}

json LoopVerificationJson(const LoopVerificationSummary& l) {
  const slam::LoopVerifierStats& v = l.counts;
  using slam::MatchRefusal;
  using slam::MatchRefusalName;
  json lv = {{"proposed", v.proposed},
             {"accepted", v.accepted},
             {"rejected", v.rejected},
             {"expired", v.expired},
             {MatchRefusalName(MatchRefusal::kNotUnique), v.not_unique},
             {"switched_off", l.switched_off},
             {"attempts", v.attempts},
             {MatchRefusalName(MatchRefusal::kFewPoints), v.few_points},
             {MatchRefusalName(MatchRefusal::kLowScore), v.low_score},
             {MatchRefusalName(MatchRefusal::kAmbiguous), v.ambiguous},
             {MatchRefusalName(MatchRefusal::kImplausible), v.implausible},
             {MatchRefusalName(MatchRefusal::kApproachDisagrees), v.approach_disagrees},
             {"beyond_window", v.beyond_window}};
  if (l.global) {
    lv["global_attempts"] = v.global_attempts;
    lv["global_proposed"] = v.global_proposed;
    lv["global_searches"] = v.global_searches;
    lv["follow_attempts"] = v.follow_attempts;
    lv["follow_proposed"] = v.follow_proposed;
  }
  if (l.injection) {
    lv["injected"] = v.injected;
    lv["injected_accepted"] = v.injected_accepted;
  }
  return lv;
}

/// The change-aware figures (issue #35): against the world's state at the end and at the
/// --present-at times, and per changing object.
void PutChangeFigures(json& j, const ModeSummary& m) {
  if (m.current_blur) {
    json b;
    Put(b, "mean_cm", m.current_blur->mean_cm);
    Put(b, "p95_cm", m.current_blur->p95_cm);
    j["current_blur"] = b;
    Put(j, "current_recall", m.current_blur->recall);
    Put(j, "stale_cells", m.stale_cells);
  }
  if (!m.present_at.empty()) {
    json list = json::array();
    for (const PresentAt& p : m.present_at) {
      json e = {{"t_s", p.t_s}};
      Put(e, "ate_rmse_m", p.ate_rmse_m);
      if (p.current_blur) {
        Put(e, "current_blur_cm", p.current_blur->mean_cm);
        Put(e, "current_recall", p.current_blur->recall);
      }
      Put(e, "stale_cells", p.stale_cells);
      Put(e, "stale_seen_cells", p.stale_seen_cells);
      Put(e, "change_recall", p.change_recall);
      Put(e, "change_recall_seen", p.change_recall_seen);
      list.push_back(e);
    }
    j["present_at"] = list;
  }
  if (m.change) {
    Put(j, "change_recall", m.change->recall);
    j["change_recall_seen"] = m.change->recent;
    Put(j, "stale_seen_cells", m.change->stale_seen);
    json objects = json::object();
    for (const auto& [name, o] : m.change->objects) {
      json e = json::object();
      Put(e, "shows_present", o.shows_present);
      Put(e, "since_seen_s", o.since_seen_s);
      Put(e, "present_shown", o.present_shown);
      Put(e, "past_shown", o.past_shown);
      if (o.shows_present) {
        e["present_seen_cells"] = o.present_seen_cells;
        e["past_seen_cells"] = o.past_seen_cells;
      }
      objects[name] = e;
    }
    j["changes"] = objects;
  }
}

json SequentialJson(const SequentialSummary& s) {
  return {{"count", s.count}, {"matched", s.matched},     {"degenerate", s.degenerate},
          {"weak", s.weak},   {"recovered", s.recovered}, {"lost", s.lost}};
}

}  // namespace

json ModeSummaryJson(const ModeSummary& m) {
  json j = json::object();
  Put(j, "observations", m.observations);
  Put(j, "wall_time_s", m.wall_time_s);
  if (m.time_per_obs_ms) j["time_per_obs_ms"] = TimeJson(*m.time_per_obs_ms);
  Put(j, "nodes_final", m.nodes_final);
  Put(j, "edges_final", m.edges_final);
  Put(j, "nodes_max", m.nodes_max);
  Put(j, "edges_max", m.edges_max);
  Put(j, "nodes_after_first_pass", m.nodes_after_first_pass);
  if (!m.edges_by_kind.empty()) j["edges_by_kind"] = m.edges_by_kind;
  Put(j, "gamma_final", m.gamma_final);
  Put(j, "scans_kept_pct", m.scans_kept_pct);
  Put(j, "peak_rss_mb", m.peak_rss_mb);
  Put(j, "graph_bytes_final", m.graph_bytes_final);
  if (m.blur) {
    json b = {{"thickness", m.blur->thickness}};
    Put(b, "mean_cm", m.blur->mean_cm);
    Put(b, "p95_cm", m.blur->p95_cm);
    Put(b, "recall", m.blur->recall);
    j["blur"] = b;
  }
  PutChangeFigures(j, m);
  Put(j, "ate_rmse_m", m.ate_rmse_m);
  if (m.rpe_1m) {
    j["rpe_1m"] = {{"count", m.rpe_1m->count},
                   {"trans_rmse_m", m.rpe_1m->trans_rmse_m},
                   {"rot_rmse_deg", m.rpe_1m->rot_rmse_deg}};
  }
  Put(j, "reference_matched", m.reference_matched);
  if (m.sequential) j["sequential"] = SequentialJson(*m.sequential);
  Put(j, "loop_precision", m.loop_precision);
  Put(j, "loop_recall", m.loop_recall);
  Put(j, "loop_precision_last_hour", m.loop_precision_last_hour);
  if (m.loop_verification) {
    j["loop_verification"] = LoopVerificationJson(*m.loop_verification);
  }
  if (m.relations) {
    const RelationsSummary& r = *m.relations;
    j["relations"] = {{"count", r.count},
                      {"trans_mean_m", r.trans_mean_m},
                      {"trans_std_m", r.trans_std_m},
                      {"rot_mean_deg", r.rot_mean_deg},
                      {"rot_std_deg", r.rot_std_deg}};
  }
  if (m.kld) {
    j["kld"] = {{"count", m.kld->count},
                {"mean", m.kld->mean},
                {"max", m.kld->max},
                {"infinite", m.kld->infinite},
                {"mean_finite", m.kld->mean_finite}};
  }
  if (!m.stage_ms.empty()) j["stage_ms"] = m.stage_ms;
  Put(j, "map_entropy_bits", m.map_entropy_bits);
  Put(j, "occupied_share", m.occupied_share);
  Put(j, "scan_cells", m.scan_cells);
  Put(j, "scan_cells_reference", m.scan_cells_reference);
  return j;
}

std::map<std::string, std::int64_t> EdgesByKind(const slam::PoseGraph& graph) {
  std::map<std::string, std::int64_t> out;
  for (const slam::PoseEdge& e : graph.edges()) {
    ++out[EdgeKindName(e.kind)];
  }
  for (const slam::CliqueFactor& c : graph.cliques()) {
    out["clique_pairs"] += static_cast<std::int64_t>(c.nodes.size() * (c.nodes.size() - 1) / 2);
  }
  return out;
}

std::optional<TimeStats> ComputeTimeStats(const std::vector<TimelineRow>& rows,
                                          std::optional<int> first_pass_end_obs) {
  if (rows.empty()) return std::nullopt;
  std::vector<double> ms, first;
  for (const TimelineRow& r : rows) {
    ms.push_back(r.time_ms);
    if (first_pass_end_obs && r.obs < *first_pass_end_obs) first.push_back(r.time_ms);
  }
  TimeStats t;
  t.mean = Mean(ms);
  t.p50 = Percentile(ms, 0.5);
  t.p95 = Percentile(ms, 0.95);
  t.max = *std::max_element(ms.begin(), ms.end());
  if (!first.empty()) t.first_pass_mean = Mean(first);
  const std::size_t last = (ms.size() + 9) / 10;  // ceil(10%), at least one
  t.last10_mean = Mean(std::vector<double>(ms.end() - static_cast<std::ptrdiff_t>(last), ms.end()));
  return t;
}

ModeSummary SummarizeTimeline(const std::vector<TimelineRow>& rows,
                              std::optional<int> first_pass_end_obs) {
  ModeSummary m;
  m.observations = static_cast<std::int64_t>(rows.size());
  if (rows.empty()) return m;
  m.time_per_obs_ms = ComputeTimeStats(rows, first_pass_end_obs);
  std::int64_t nmax = 0, emax = 0;
  double rss = 0.0;
  for (const TimelineRow& r : rows) {
    nmax = std::max<std::int64_t>(nmax, r.nodes);
    emax = std::max<std::int64_t>(emax, r.edges);
    rss = std::max(rss, r.rss_mb);
    if (first_pass_end_obs && r.obs < *first_pass_end_obs) m.nodes_after_first_pass = r.nodes;
  }
  m.nodes_final = rows.back().nodes;
  m.edges_final = rows.back().edges;
  m.nodes_max = nmax;
  m.edges_max = emax;
  m.gamma_final = rows.back().gamma;
  m.graph_bytes_final = static_cast<std::int64_t>(rows.back().graph_bytes);
  m.peak_rss_mb = rss;
  m.stage_ms = StageTotals(rows);
  return m;
}

std::map<std::string, double> StageTotals(const std::vector<TimelineRow>& rows) {
  std::map<std::string, double> t;
  for (const char* k : {"matching", "loop_closing", "optimization", "map_update", "gains",
                        "marginalization", "other"}) {
    t[k] = 0.0;
  }
  for (const TimelineRow& r : rows) {
    t["matching"] += r.stages.match_ms;
    t["loop_closing"] += r.stages.loop_ms;
    t["optimization"] += r.stages.backend_ms;
    t["map_update"] += r.stages.map_update_ms;
    t["gains"] += r.stages.gain_ms;
    t["marginalization"] += r.stages.marginalize_ms;
    t["other"] += r.time_ms - r.stages.Sum();
  }
  return t;
}

std::optional<KldSummary> SummarizeKld(const std::vector<double>& kl_values) {
  if (kl_values.empty()) return std::nullopt;
  KldSummary k;
  k.count = static_cast<std::int64_t>(kl_values.size());
  k.mean = Mean(kl_values);
  k.max = *std::max_element(kl_values.begin(), kl_values.end());
  std::vector<double> finite;
  for (double v : kl_values) {
    if (std::isfinite(v)) {
      finite.push_back(v);
    } else {
      ++k.infinite;
    }
  }
  if (!finite.empty()) k.mean_finite = Mean(finite);
  return k;
}

std::string SummaryJsonText(const RunSummary& s) {
  json j = {{"source", s.source}, {"wall_time_s", s.wall_time_s}};
  Put(j, "seed", s.seed);
  Put(j, "log_duration_s", s.log_duration_s);
  if (s.log) {
    json log = {{"scans", s.log->scans},
                {"backward_stamps", s.log->backward_stamps},
                {"distinct_stamps", s.log->distinct_stamps},
                {"odometry_lost", s.log->odometry_lost}};
    Put(log, "relations_offset_s", s.log->relations_offset_s);
    Put(log, "relations_offset_detected", s.log->relations_offset_detected);
    Put(log, "relations_in_file", s.log->relations_in_file);
    Put(log, "reference", s.log->reference);
    Put(log, "reference_poses", s.log->reference_poses);
    Put(log, "draw_seed", s.log->draw_seed);
    j["log"] = log;
  }
  if (s.simulation) {
    const SimulationOutcome& o = *s.simulation;
    json sim = {{"failed", o.Failed()},
                {"collided", o.collided},
                {"timed_out", o.timed_out},
                {"collisions_expected", o.collisions_expected},
                {"collisions", o.collisions},
                {"duration_s", o.duration_s},
                {"expected_duration_s", o.expected_duration_s}};
    if (o.first_collision_s) {
      sim["first_collision"] = {{"t_s", *o.first_collision_s},
                                {"with", o.first_collision_with.value_or("")}};
    }
    j["simulation"] = sim;
  }
  if (!s.mode_order.empty()) j["mode_order"] = s.mode_order;
  json modes = json::object();
  for (const auto& [name, mode] : s.modes) modes[name] = ModeSummaryJson(mode);
  j["modes"] = modes;
  return j.dump(2) + "\n";
}

void WriteSummaryJson(const std::string& path, const RunSummary& summary) {
  io::WriteFileAtomically(path, SummaryJsonText(summary));
}

void WriteTimelineCsv(const std::string& path, const std::vector<TimelineRow>& rows) {
  // The contract's columns, then this project's additions (documented in docs/output-contract.md).
  std::string text =
      "obs,t_s,time_ms,nodes,edges,gamma,rss_mb,graph_bytes,loop_closures,optimize_ms,"
      "nodes_removed,match_ms,loop_ms,backend_ms,map_update_ms,gain_ms,marginalize_ms,"
      "sequential,odometry_lost\n";
  char line[416];
  for (const TimelineRow& r : rows) {
    std::snprintf(
        line, sizeof(line),
        "%d,%.6f,%.6g,%d,%d,%.9g,%.6g,%zu,%d,%.6g,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s,%d\n", r.obs,
        r.t_s, r.time_ms, r.nodes, r.edges, r.gamma, r.rss_mb, r.graph_bytes, r.loop_closures,
        r.optimize_ms, r.nodes_removed, r.stages.match_ms, r.stages.loop_ms, r.stages.backend_ms,
        r.stages.map_update_ms, r.stages.gain_ms, r.stages.marginalize_ms, r.sequential,
        r.odometry_lost ? 1 : 0);
    text += line;
  }
  io::WriteFileAtomically(path, text);
}

}  // namespace lifelong::eval
