#include "eval/sweep/sweep_collect.hpp"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;
// ordered_json keeps summary.json's key order for the columns.
using json = nlohmann::ordered_json;

// Every number of an object, keys joined by '/', in file order (arrays are skipped).
void Flatten(const json& j, const std::string& prefix,
             std::vector<std::pair<std::string, double>>* out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "/" + it.key();
    if (it->is_object()) {
      Flatten(*it, key, out);
    } else if (it->is_number()) {  // not booleans, strings or arrays
      out->emplace_back(key, it->get<double>());
    }
  }
}

json ReadJson(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  try {
    return json::parse(s.str());
  } catch (const json::exception& e) {
    throw InputError(p.string(), 0, "", std::string("not JSON: ") + e.what());
  }
}

// Groups of runs with the same source, settings and mode, in first-seen order.
using GroupKey = std::tuple<std::string, SweepSettings, std::string>;

template <class Values>
SweepStatsRow StatsOf(const GroupKey& key, const std::vector<Values>& members) {
  SweepStatsRow row{
      std::get<0>(key), std::get<2>(key), std::get<1>(key), static_cast<int>(members.size()), {}};
  std::map<std::string, std::vector<double>> values;
  for (const auto& m : members) {
    for (const auto& [fig, v] : m) values[fig].push_back(v);
  }
  for (const auto& [fig, v] : values) row.figures[fig] = ComputeStats(v);
  return row;
}

template <class Values>
std::vector<SweepStatsRow> Group(const std::vector<std::pair<GroupKey, Values>>& items) {
  std::vector<GroupKey> order;
  std::map<GroupKey, std::vector<Values>> groups;
  for (const auto& [key, values] : items) {
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(values);
  }
  std::vector<SweepStatsRow> rows;
  for (const GroupKey& key : order) rows.push_back(StatsOf(key, groups[key]));
  return rows;
}

}  // namespace

SweepTables CollectSweepTables(const std::string& dir) {
  SweepTables t;
  t.plan = ReadSweepPlan(dir);
  std::set<std::string> seen_figures;
  using Figures = std::map<std::string, double>;
  std::vector<std::pair<GroupKey, Figures>> absolute, paired;
  for (const SweepPlanCell& cell : t.plan.cells) {
    const fs::path cell_dir = fs::path(dir) / "cells" / cell.name;
    if (FinishedCellHash(cell_dir.string()) != cell.hash) {
      t.missing.push_back(cell.name);
      continue;
    }
    const json summary = ReadJson(cell_dir / "summary.json");
    // A run whose robot collided or timed out did not drive its scenario: never aggregated,
    // even when its cell was stamped (a result of a version that exited 0 for it).
    if (summary.contains("simulation") && summary["simulation"].value("failed", false)) {
      t.missing.push_back(cell.name);
      continue;
    }
    std::optional<std::int64_t> seed = cell.seed;
    if (!seed && summary.contains("seed") && summary["seed"].is_number_integer()) {
      seed = summary["seed"].get<std::int64_t>();
    }
    const json& modes = summary.contains("modes") ? summary["modes"] : json::object();
    std::map<std::string, Figures> by_mode;
    for (const std::string& mode : t.plan.modes) {
      if (!modes.contains(mode) || !modes[mode].is_object()) continue;
      std::vector<std::pair<std::string, double>> flat;
      Flatten(modes[mode], "", &flat);
      Figures figures(flat.begin(), flat.end());
      for (const auto& [fig, v] : flat) {
        if (seen_figures.insert(fig).second) t.figures.push_back(fig);
      }
      t.runs.push_back({cell.name, cell.source, mode, seed, cell.settings, figures});
      absolute.push_back({{cell.source, cell.settings, mode}, figures});
      by_mode[mode] = std::move(figures);
    }
    const auto base = by_mode.find(t.plan.baseline);
    for (const std::string& mode : t.plan.modes) {
      if (mode == t.plan.baseline || base == by_mode.end() || !by_mode.count(mode)) continue;
      Figures diff;
      for (const auto& [fig, v] : by_mode[mode]) {
        const auto b = base->second.find(fig);
        if (b != base->second.end()) diff[fig] = v - b->second;
      }
      paired.push_back({{cell.source, cell.settings, mode}, diff});
    }
  }
  t.aggregate = Group(absolute);
  t.paired = Group(paired);
  return t;
}

}  // namespace lifelong::eval
