// Runs of beams for change detection (change_runs.hpp).
#include "slam/grid/change_runs.hpp"

#include <algorithm>
#include <cmath>

namespace lifelong::slam::change_runs {
namespace {

/// Whether returns j and j + 1 of `scan` lie on one surface: both returns, at most max_gap_m
/// apart.
bool OneSurface(const LaserScan& scan, std::uint32_t j, double max_gap_m) {
  if (j + 1 >= scan.ranges_m.size() || !scan.IsReturn(j) || !scan.IsReturn(j + 1)) return false;
  const double a = scan.ranges_m[j], b = scan.ranges_m[j + 1];
  const double gap2 = a * a + b * b - 2.0 * a * b * std::cos(scan.angle_increment_rad);
  return gap2 <= max_gap_m * max_gap_m;
}

}  // namespace

void KeepRunsToTheEdge(std::size_t min_run, const LaserScan& newer,
                       const std::vector<std::uint32_t>& unseen, double max_gap_m,
                       Occlusion occlusion, std::vector<std::uint32_t>* v) {
  // How many returns past `from` (step -1 or +1) are unseen and on its surface.
  const auto beyond = [&](std::uint32_t from, long step) {
    std::size_t n = 0;
    for (long j = static_cast<long>(from) + step;
         j >= 0 && j < static_cast<long>(newer.ranges_m.size()); j += step) {
      const auto b = static_cast<std::uint32_t>(j);
      if (!std::binary_search(unseen.begin(), unseen.end(), b)) break;
      if (!OneSurface(newer, static_cast<std::uint32_t>(std::min(j, j - step)), max_gap_m)) break;
      ++n;
    }
    return n;
  };
  // The newer scan's own view ends beyond `from` on the side of `step` (Occludes).
  const auto occluded = [&](std::uint32_t from, long step) {
    const long j = static_cast<long>(from) + step;
    return j >= 0 && Occludes(newer, static_cast<std::size_t>(j), from, occlusion.hidden_m);
  };
  KeepRuns(min_run, v, [&](std::uint32_t first, std::uint32_t last, std::size_t count) {
    if (occlusion.min_run > 0 && count >= occlusion.min_run &&
        (occluded(first, -1) || occluded(last, +1))) {
      return min_run;
    }
    return beyond(first, -1) + beyond(last, +1);
  });
}

}  // namespace lifelong::slam::change_runs
