// `lifelong sweep collect DIR`: the results of a sweep's cells as tables.
//   runs.csv       one row per cell × mode: cell, source, seed, mode, each setting, and
//                  every number of the cell's summary.json mode object, nested keys joined
//                  by '/' (blur/mean_cm); the union of columns, empty where absent.
//   aggregate.csv  one row per source × setting × mode: n (runs), and per figure
//                  <fig>/mean, /std, /ci95_low, /ci95_high (Student t over the seeds) and
//                  /n (runs that have the figure). Empty where it cannot be computed.
//   paired.csv     the same over the per-seed differences mode − baseline (both from the
//                  same cell, so the same simulated world, route and noise).
// Only cells whose recorded hash equals the plan's are read: a stale or failed cell is
// listed as missing, never mixed in.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "eval/sweep/sweep_plan.hpp"
#include "eval/sweep/sweep_stats.hpp"

namespace lifelong::eval {

using SweepSettings = std::vector<std::pair<std::string, std::string>>;

struct SweepRunRow {
  std::string cell, source, mode;
  std::optional<std::int64_t> seed;
  SweepSettings settings;
  std::map<std::string, double> figures;
};

struct SweepStatsRow {
  std::string source, mode;
  SweepSettings settings;
  int n = 0;  ///< runs in the group
  std::map<std::string, SampleStats> figures;
};

struct SweepTables {
  SweepPlan plan;
  std::vector<std::string> figures;  ///< every figure column, in first-seen order
  std::vector<SweepRunRow> runs;
  std::vector<SweepStatsRow> aggregate;
  std::vector<SweepStatsRow> paired;  ///< modes other than the baseline
  std::vector<std::string> missing;   ///< cells without a current result
};

/// Reads DIR/sweep.json and each finished cell's summary.json. Throws lifelong::InputError.
SweepTables CollectSweepTables(const std::string& dir);

/// Writes DIR/runs.csv, aggregate.csv and paired.csv (each atomically).
void WriteSweepCsvs(const SweepTables& tables, const std::string& dir);

}  // namespace lifelong::eval
