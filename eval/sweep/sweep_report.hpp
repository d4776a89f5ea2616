// DIR/report.html of a sweep: per key figure (time per observation, final nodes, blur,
// ATE) a gnuplot chart of each mode's mean with its 95 % interval per scenario and
// setting, the aggregate and paired tables of those figures, links to the CSVs and to
// every cell's own report. Figures are optional: without gnuplot the page says so.
#pragma once

#include <string>
#include <vector>

#include "eval/sweep/sweep_collect.hpp"

namespace lifelong::eval {

/// The figures the report charts and tabulates.
const std::vector<std::string>& SweepKeyFigures();

/// Writes DIR/report.html (atomically) and its charts (DIR/<figure>.png, scripts and data
/// in DIR/plot_data/). Returns the chart files written.
std::vector<std::string> WriteSweepReport(const SweepTables& tables, const std::string& dir,
                                          const std::string& gnuplot = "gnuplot");

}  // namespace lifelong::eval
