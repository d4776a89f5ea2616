// Published figures for the real logs in ../shared/datasets, shown in the report beside a
// replay's own (datasets/REFERENCE_FIGURES.md lists them with their sources). One small
// table in code: the relation errors (Kümmerle et al. 2009's metric) are keyed by the
// relations file's name, the seed's notes on a log by the log file's name.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace lifelong::eval {

/// One published result in the relations metric: mean ± std over the relations.
struct PublishedRelationError {
  std::string method;    ///< e.g. "Graph mapping"
  std::string citation;  ///< e.g. "Kümmerle et al. 2009, On measuring the accuracy ..."
  double trans_mean_m = 0.0, trans_std_m = 0.0;
  std::optional<double> rot_mean_deg, rot_std_deg;  ///< absent where not published
};

struct ReferenceFigures {
  std::string dataset;  ///< e.g. "Intel Research Lab"
  std::string scope;    ///< what the published figures cover, e.g. the whole log
  std::vector<PublishedRelationError> relation_errors;  ///< with the matching relations file
  std::vector<std::string> notes;  ///< other published figures, each with its source
};

/// The figures for a replay: relation errors when `relations_path`'s file name is a known
/// relations file (e.g. "intel.relations"), notes when `log_path`'s file name starts with
/// a known log's stem (e.g. "intel", "fhw"). Absent when nothing is known.
std::optional<ReferenceFigures> FindReferenceFigures(const std::string& relations_path,
                                                     const std::string& log_path);

}  // namespace lifelong::eval
