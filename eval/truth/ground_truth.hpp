// What is known of the truth of a simulated run: the surfaces map metrics score a map against.
#pragma once

#include <memory>
#include <vector>

#include "sim/world.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

class TruthRaster;

/// What is known of the truth (simulation only).
struct GroundTruth {
  /// Every surface that stood during the run (TrueWalls), world frame: blur and recall.
  std::vector<Segment> walls;
  /// The surfaces standing at the run's end (WallsAt) and those gone by then (GoneSurfaces):
  /// current_blur, current_recall and stale_cells. Empty gone: the world did not change.
  std::vector<Segment> walls_now;
  std::vector<Segment> gone;
  /// The simulated world and the run's end, for change_recall (eval/metrics/change_recall.hpp);
  /// none when the truth came from files.
  std::shared_ptr<const sim::World> world;
  double end_s = 0.0;
  /// These surfaces and the run's true trajectory rasterized at the map resolution, made
  /// once per run (eval/truth/truth_raster.hpp) and read by every mode's scoring; none: a
  /// scorer rasterizes for itself.
  std::shared_ptr<const TruthRaster> raster;
};

}  // namespace lifelong::eval
