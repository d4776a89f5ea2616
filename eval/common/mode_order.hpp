// The one order in which a run's modes are shown: in tables, figures' legends and the report.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace lifelong::eval {

/// The keys of `by_mode` (a map from mode name), those named in `order` first and in that
/// order (each once), then the others in the map's order.
template <class Map>
std::vector<std::string> ModesInOrder(const Map& by_mode, const std::vector<std::string>& order) {
  std::vector<std::string> out;
  const auto listed = [&out](const std::string& m) {
    return std::find(out.begin(), out.end(), m) != out.end();
  };
  for (const std::string& m : order) {
    if (by_mode.count(m) != 0 && !listed(m)) out.push_back(m);
  }
  for (const auto& entry : by_mode) {
    if (!listed(entry.first)) out.push_back(entry.first);
  }
  return out;
}

}  // namespace lifelong::eval
