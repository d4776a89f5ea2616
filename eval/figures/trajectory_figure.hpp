// The figure of a log scored against a reference trajectory: the reference (black, thick)
// and each mode's estimate moved onto it by its ATE alignment (in the mode's colour), in
// the reference's frame, with a scale bar and a key. `trajectories.png` in the report.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sensor/pose2.hpp"

namespace lifelong::eval {

/// One mode's estimate, already aligned onto the reference.
struct AlignedTrack {
  std::string mode;
  std::vector<Pose2> poses;
};

/// Writes the figure as a PNG (atomically) of at most max_side_px on its longer side.
/// Throws InputError naming the path when it cannot be written.
void WriteTrajectoryFigure(const std::string& path, const std::vector<Pose2>& reference,
                           const std::string& reference_name,
                           const std::vector<AlignedTrack>& tracks, int max_side_px = 900);

}  // namespace lifelong::eval
