#include "slam/removal/removal_policy.hpp"

#include <algorithm>

namespace lifelong::slam {
namespace {

struct Entry {
  const char* name;
  std::unique_ptr<RemovalPolicy> (*make)(const RemovalPolicyConfig&);
};
constexpr Entry kRegistry[] = {{"information-gain", MakeInformationGainPolicy},
                               {"node-budget", MakeNodeBudgetPolicy},
                               {"overlap", MakeOverlapPolicy},
                               {"dpg", MakeDpgPolicy}};

}  // namespace

std::unique_ptr<RemovalPolicy> MakeRemovalPolicy(const std::string& name,
                                                 const RemovalPolicyConfig& config) {
  for (const Entry& e : kRegistry) {
    if (name == e.name) return e.make(config);
  }
  return nullptr;
}

std::vector<std::string> RemovalPolicyNames() {
  std::vector<std::string> names;
  for (const Entry& e : kRegistry) names.emplace_back(e.name);
  return names;
}

std::map<NodeId, double>::const_iterator LowestGain(const std::map<NodeId, double>& gains) {
  // std::map iterates ids ascending, and min_element keeps the first of equal gains.
  return std::min_element(gains.begin(), gains.end(),
                          [](const auto& a, const auto& b) { return a.second < b.second; });
}

}  // namespace lifelong::slam
