// The summary table of report.html, as a reader of the seed's chapter 6 expects it: the
// figures of summary.json in four groups (runtime; graph and memory; accuracy; map
// quality), each row with its unit and a one-line definition, one column per mode in the
// run's --modes order, and each mode's ratio to the baseline (the first of those modes)
// where a ratio means something (times, sizes, errors; not counts of observations, shares
// or KL divergences). A row no mode has is left out, and so is a group with no row left.
// A compact table of the key figures leads the report; this one is folded below it.
#pragma once

#include <string>
#include <vector>

#include "eval/metrics/summary.hpp"

namespace lifelong::eval {

/// One row of the table: a figure of summary.json (a JSON pointer into a mode's object).
struct TableRow {
  const char* group;       ///< e.g. "Runtime"
  const char* pointer;     ///< e.g. "/time_per_obs_ms/mean"
  const char* label;       ///< e.g. "time per observation, mean"
  const char* unit;        ///< e.g. "ms" ("" for a count)
  double scale;            ///< shown value = JSON value * scale (e.g. 100 for m -> cm)
  bool ratio;              ///< show value / baseline's value
  const char* definition;  ///< one line
};

/// Every row the table can show, in order, grouped.
const std::vector<TableRow>& SummaryTableRows();

/// The modes of `summary` in display order, the one order every table and figure uses: those
/// of summary.mode_order (the run's --modes) that ran, in that order, then any others
/// alphabetically. The first is the baseline.
std::vector<std::string> OrderedModes(const RunSummary& summary);

/// The table as HTML (<table class="summary">...</table> and a note on the ratios and
/// the marks). A stage's time of 0 reads "not run"; no ratio is taken against a time
/// under 1 ms; "relations used" reads "N of M" (M: summary.log->relations_in_file), marked
/// class "warn" when fewer than half were used; a missing precision reads "no closures"
/// when the mode accepted none.
std::string SummaryTableHtml(const RunSummary& summary);

/// The pointers of the key figures, in the compact table's order (a dozen of the rows:
/// time per observation mean and last 10 %, mapper time, nodes and edges final, scans
/// kept, ATE, blur, loop precision and recall, relations used and their translation
/// error, peak memory).
const std::vector<std::string>& KeyFigurePointers();

/// The compact table of the key figures that any mode has (<table class="summary key">),
/// formatted as SummaryTableHtml's, each definition in its label's tooltip.
std::string KeyTableHtml(const RunSummary& summary);

/// A value as shown: integers in full, others with 3 significant digits (whole numbers
/// from 1000 on).
std::string FormatValue(double value, bool is_integer);

/// A ratio as shown, e.g. "0.25×", "28×".
std::string FormatRatio(double ratio);

}  // namespace lifelong::eval
