// The modes' table (mode.hpp).
#include "slam/mapping/mode.hpp"

#include <algorithm>
#include <stdexcept>

#include "slam/removal/removal_policy.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

const std::vector<Mode>& NamedModes() {
  static const std::vector<Mode> kModes = {
      {"standard", "", ""},
      {"pruned", "information-gain", "chow-liu"},  // the seed
      {"pruned-exact", "information-gain", "exact"},
      {"pruned-naive", "information-gain", "naive"},
      {"pruned-glc", "information-gain", "glc"},
      {"pruned-nfr", "information-gain", "nfr-subgraph"},
      {"pruned-overlap", "overlap", "chow-liu"},  // slam_toolbox's lifelong rule
      {"pruned-dpg", "dpg", "chow-liu"},          // DPG-SLAM's change detection
  };
  return kModes;
}

Mode NamedMode(const std::string& name) {
  for (const Mode& m : NamedModes()) {
    if (m.name == name) return m;
  }
  throw std::invalid_argument("no mode named '" + name + "'");
}

std::optional<Mode> ParseMode(const std::string& name) {
  for (const Mode& m : NamedModes()) {
    if (m.name == name) return m;
  }
  const std::size_t plus = name.find('+');
  if (plus == std::string::npos) return std::nullopt;
  Mode m{name, name.substr(0, plus), name.substr(plus + 1)};
  const auto known = [](const std::vector<std::string>& names, const std::string& n) {
    return std::find(names.begin(), names.end(), n) != names.end();
  };
  if (!known(RemovalPolicyNames(), m.policy) || !known(SparsifierNames(), m.sparsifier)) {
    return std::nullopt;
  }
  return m;
}

std::string ModeList() {
  std::string list;
  for (const Mode& m : NamedModes()) list += (list.empty() ? "" : ", ") + m.name;
  const auto join = [](const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
  };
  return list + ", or POLICY+SPARSIFIER (policies: " + join(RemovalPolicyNames()) +
         "; sparsifiers: " + join(SparsifierNames()) + ")";
}

}  // namespace lifelong::slam
