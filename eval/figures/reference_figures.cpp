#include "eval/figures/reference_figures.hpp"

#include <filesystem>

namespace lifelong::eval {
namespace {

const char kKuemmerle[] =
    "Kümmerle et al. 2009, \"On measuring the accuracy of SLAM algorithms\", Autonomous "
    "Robots 27(4)";
const char kHess[] =
    "Hess et al. 2016, \"Real-time loop closure in 2D LIDAR SLAM\" (Cartographer), ICRA";
const char kSeed[] =
    "Kretzschmar 2009, \"Life-long Map Learning for Graph-based SLAM\", Diplomarbeit";

struct Entry {
  const char* relations_file;  ///< "" when the log has no relations file
  const char* log_stem;        ///< a log file name starting with this matches
  ReferenceFigures figures;
};

std::vector<Entry> Table() {
  return {
      {"intel.relations",
       "intel",
       {"Intel Research Lab",
        "the published figures are over the whole log (2691 s); a replay of a part of it "
        "uses only the relations inside that part",
        {{"Cartographer", kHess, 0.0229, 0.0239, 0.453, 1.335},
         {"Graph mapping", kKuemmerle, 0.031, 0.026, 1.3, 4.7},
         {"RBPF (GMapping)", kKuemmerle, 0.070, 0.083, std::nullopt, std::nullopt},
         {"Scan matching only", kKuemmerle, 0.220, 0.296, std::nullopt, std::nullopt}},
        {std::string("Seed §6.4.1 (") + kSeed +
             "): the pruned mapper kept 29 % of the scans; the whole log took 537 s standard "
             "vs 314 s pruned on 2009 hardware (compare ratios, not seconds).",
         std::string("Seed §6.2, Fig. 6.6: the final Intel graph has 13052 edges with exact "
                     "marginalization and 559 with Chow-Liu trees (") +
             kSeed + ").",
         std::string("Cartographer: 179 s wall time for the 2691 s log (Xeon E5-1650, several "
                     "threads) and 97.2 % loop-closure precision (") +
             kHess + ")."}}},
      {"",
       "fhw",
       {"FHW Museum",
        "the whole log",
        {},
        {std::string("Seed §6.4.3 (") + kSeed +
         "): the pruned mapper kept 21 % of the scans; 32 min 45 s standard vs 5 min 19 s "
         "pruned on 2009 hardware (compare ratios, not seconds)."}}},
  };
}

}  // namespace

std::optional<ReferenceFigures> FindReferenceFigures(const std::string& relations_path,
                                                     const std::string& log_path) {
  namespace fs = std::filesystem;
  const std::string relations = fs::path(relations_path).filename().string();
  const std::string log = fs::path(log_path).filename().string();
  for (Entry& e : Table()) {
    ReferenceFigures out = e.figures;
    const bool relations_match = !relations.empty() && relations == e.relations_file;
    if (!relations_match) out.relation_errors.clear();
    if (log.rfind(e.log_stem, 0) != 0) out.notes.clear();
    if (!out.relation_errors.empty() || !out.notes.empty()) return out;
  }
  return std::nullopt;
}

}  // namespace lifelong::eval
