// Runs of beams for change detection (change_detection.hpp): a change covers neighbouring
// beams, noise and pose error single ones, so the beams that show a change count only in
// runs; how long a run must be, and what counts toward it where a view cuts it short.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sensor/laser_scan.hpp"
#include "slam/grid/beam_cut.hpp"

namespace lifelong::slam::change_runs {

inline std::uint32_t BeamOf(std::uint32_t b) { return b; }
inline std::uint32_t BeamOf(const BeamCut& c) { return c.beam; }

/// Keeps the beams (ascending) that lie in runs of at least min_run beams, a run allowing
/// gaps of one beam: a change covers neighbouring beams, noise single ones. A run of `count`
/// beams from beam `first` to beam `last` counts extra(first, last, count) more toward min_run.
template <typename T, typename Extra>
void KeepRuns(std::size_t min_run, std::vector<T>* v, Extra&& extra) {
  std::vector<T> kept;
  std::size_t start = 0;
  for (std::size_t i = 1; i <= v->size(); ++i) {
    if (i < v->size() && BeamOf((*v)[i]) - BeamOf((*v)[i - 1]) <= 2) continue;
    const std::size_t count = i - start;
    const std::size_t n = count + extra(BeamOf((*v)[start]), BeamOf((*v)[i - 1]), count);
    if (n >= min_run) kept.insert(kept.end(), v->begin() + start, v->begin() + i);
    start = i;
  }
  *v = std::move(kept);
}

template <typename T>
void KeepRuns(std::size_t min_run, std::vector<T>* v) {
  KeepRuns(min_run, v, [](std::uint32_t, std::uint32_t, std::size_t) { return std::size_t{0}; });
}

/// Whether return j of `scan` lies more than hidden_m nearer than return i: a nearer surface
/// (a doorway's jamb) hides what lies beyond i on j's side.
inline bool Occludes(const LaserScan& scan, std::size_t j, std::size_t i, double hidden_m) {
  return j < scan.ranges_m.size() && scan.IsReturn(j) &&
         scan.ranges_m[j] < scan.ranges_m[i] - hidden_m;
}

/// When a run that the newer scan's own view cuts short is taken as whole.
struct Occlusion {
  std::size_t min_run = 0;  ///< the run a glimpse needs (0: none is taken as such)
  double hidden_m = 0.0;    ///< how much nearer the return beyond its end must be
};

/// KeepRuns for the newer scan's added returns (ascending), where a run that reaches the
/// edge of the older scan's field of view is cut short by it, not by the world: it counts
/// the returns on the same surface (OneSurface) beyond that edge, which the older scan could
/// not judge (`unseen`, ascending), toward min_run. A box seen by the older scan's outermost
/// beams shows few of its returns inside that scan's view. Likewise a run that the newer
/// scan's own view cuts short, the beam beyond one of its ends returning more than
/// occlusion.hidden_m nearer (a desk glimpsed through a doorway past its jamb), needs only
/// occlusion.min_run returns: its length says how much the robot could see, not how wide
/// the object is.
void KeepRunsToTheEdge(std::size_t min_run, const LaserScan& newer,
                       const std::vector<std::uint32_t>& unseen, double max_gap_m,
                       Occlusion occlusion, std::vector<std::uint32_t>* v);

}  // namespace lifelong::slam::change_runs
