// Validate(MapperConfig): every setting against its allowed values, as declared once in
// mapper_config_fields.hpp, then the bounds across settings (the matchers' tables, the place
// descriptors). eval's config reader only maps keys to fields, and names the line of the
// field this finds.
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "slam/mapping/config_checker.hpp"
#include "slam/mapping/mapper_config.hpp"
#include "slam/mapping/mapper_config_fields.hpp"
#include "slam/matching/incremental_config.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {
namespace {

using namespace config_fields;  // NOLINT: the fields are this file's vocabulary

std::string Gib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3g GiB", bytes / 1073741824.0);
  return buf;
}

// The products of settings that size a matcher's allocations (EstimateFootprint), for the
// incremental matcher and for the loop closer's widest and refining searches.
std::optional<ConfigProblem> CheckMatcher(const std::string& where, const MatcherConfig& m,
                                          double window_m, const char* window_key,
                                          double window_rad, const char* window_rad_key) {
  const MatcherFootprint f = EstimateFootprint(m, window_m, window_rad);
  const std::string limit = Gib(kMaxMatcherBytes);
  if (f.table_bytes > kMaxMatcherBytes) {
    return ConfigProblem{
        std::string(window_key) + ", " + where + ".resolution_m, " + where + ".coarse_factor",
        "the matcher's tables over this window would take " + Gib(f.table_bytes) + ", more than " +
            limit + ": a narrower window or coarser cells"};
  }
  if (f.frontier_bytes > kMaxMatcherBytes) {
    return ConfigProblem{std::string(window_key) + ", " + window_rad_key + ", " + where +
                             ".angular_step_rad, " + where + ".resolution_m",
                         "the matcher's search frontier (rotations x blocks) would take " +
                             Gib(f.frontier_bytes) + ", more than " + limit +
                             ": narrower windows, a coarser step or a larger coarse_factor"};
  }
  return std::nullopt;
}

// Every node keeps its place descriptor (rings x sectors floats) while the global search is
// on: 10^4 bins is 40 kB a node, 400 MB for 10^4 nodes.
constexpr int kMaxDescriptorBins = 10000;

std::optional<ConfigProblem> CheckFootprints(const MapperConfig& c) {
  const PlaceDescriptorConfig& d = c.loops.global.descriptor;
  if (static_cast<long long>(d.rings) * d.sectors > kMaxDescriptorBins) {
    return ConfigProblem{"loops.global.rings, loops.global.sectors",
                         "a place descriptor of " + std::to_string(d.rings) + " x " +
                             std::to_string(d.sectors) + " bins is kept for every node: at most " +
                             std::to_string(kMaxDescriptorBins) + " bins"};
  }
  const MatcherConfig& inc = c.incremental.matcher;
  const LoopClosingConfig& lc = c.loops;
  if (auto p = CheckMatcher("incremental.matcher", inc, inc.linear_window_m,
                            "incremental.matcher.linear_window_m", inc.angular_window_rad,
                            "incremental.matcher.angular_window_rad")) {
    return p;
  }
  if (auto p = CheckMatcher("incremental.matcher", inc, c.incremental.lost_window_m,
                            "incremental.lost_window_m", kLostStepWindowRad,
                            "a full turn (a lost step)")) {
    return p;
  }
  if (auto p = CheckMatcher("loops.matcher", lc.matcher, lc.max_window_m, "loops.max_window_m",
                            lc.max_window_rad, "loops.max_window_rad")) {
    return p;
  }
  if (auto p = CheckMatcher("loops.matcher", lc.matcher, lc.global.linear_window_m,
                            "loops.global.linear_window_m", lc.global.angular_window_rad,
                            "loops.global.angular_window_rad")) {
    return p;
  }
  return CheckMatcher("loops.matcher", lc.matcher, lc.refine_window_m, "loops.refine_window_m",
                      lc.refine_window_rad, "loops.refine_window_rad");
}

}  // namespace

std::optional<ConfigProblem> Validate(const MapperConfig& config) {
  MapperConfig c = config;  // the visitors take fields by reference
  Checker checker;
  VisitConfig(checker, c);
  if (checker.problem()) return checker.problem();
  // A mode is a named one or POLICY+SPARSIFIER (mode.hpp); an edited copy must stay one.
  const std::optional<Mode> parsed = ParseMode(c.pruning.mode.name);
  if (!parsed || parsed->policy != c.pruning.mode.policy ||
      parsed->sparsifier != c.pruning.mode.sparsifier) {
    return ConfigProblem{"pruning.mode", "'" + c.pruning.mode.name + "' (policy '" +
                                             c.pruning.mode.policy + "', sparsifier '" +
                                             c.pruning.mode.sparsifier +
                                             "') is not a mode: " + ModeList()};
  }
  return CheckFootprints(c);
}

}  // namespace lifelong::slam
