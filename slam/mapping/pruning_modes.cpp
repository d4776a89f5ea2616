// The mapper's modes by name, and the sparsifier each one uses (mapper_config.hpp).
#include <string>
#include <vector>

#include "slam/mapping/mapper_config.hpp"

namespace lifelong::slam {
namespace {

// A mode is a removal policy and a sparsifier; an empty policy is pruning.policy's.
struct ModeEntry {
  const char* name;
  PruningMode mode;
  const char* sparsifier;
  const char* policy;
};
constexpr ModeEntry kModes[] = {{"standard", PruningMode::kNone, "", ""},
                                {"pruned", PruningMode::kChowLiu, "chow-liu", ""},
                                {"pruned-exact", PruningMode::kExact, "exact", ""},
                                {"pruned-naive", PruningMode::kNaive, "naive", ""},
                                {"pruned-glc", PruningMode::kGlc, "glc", ""},
                                {"pruned-nfr", PruningMode::kNfr, "nfr-subgraph", ""},
                                {"pruned-overlap", PruningMode::kOverlap, "chow-liu", "overlap"},
                                {"pruned-dpg", PruningMode::kDpg, "chow-liu", "dpg"}};

}  // namespace

bool ParsePruningMode(const std::string& name, PruningMode* mode) {
  for (const ModeEntry& e : kModes) {
    if (name == e.name) {
      *mode = e.mode;
      return true;
    }
  }
  return false;
}

std::string PruningModeName(PruningMode mode) {
  for (const ModeEntry& e : kModes) {
    if (mode == e.mode) return e.name;
  }
  return "unknown";
}

std::vector<std::string> PruningModeNames() {
  std::vector<std::string> names;
  for (const ModeEntry& e : kModes) names.emplace_back(e.name);
  return names;
}

std::string PruningModeList() {
  std::string list;
  for (const ModeEntry& e : kModes) list += (list.empty() ? "" : ", ") + std::string(e.name);
  return list;
}

std::string ModeSparsifier(PruningMode mode) {
  for (const ModeEntry& e : kModes) {
    if (mode == e.mode) return e.sparsifier;
  }
  return "";
}

std::string ModePolicy(PruningMode mode) {
  for (const ModeEntry& e : kModes) {
    if (mode == e.mode) return e.policy;
  }
  return "";
}

}  // namespace lifelong::slam
