// The simulated world's state at a time (issue #35): which doors are closed and where the
// boxes stand then, as segments, and the surfaces that stood during a run but are gone at
// its end. The change-aware map metrics (current_blur, current_recall, stale_cells) score a
// map against these.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eval/truth/ground_truth.hpp"
#include "sim/world.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

/// The ground truth for map metrics over a run that ends at `end_s`: static walls, the
/// doors that are closed at some time in [0, end_s] (a door open all run long is no wall
/// the robot could see), and the boxes at each pose they take by end_s.
std::vector<Segment> TrueWalls(const sim::World& world, double end_s);

/// The outline of `box` where it stands at t_s: its last move at or before t_s, else its
/// initial pose.
std::vector<Segment> BoxOutlineAt(const sim::Box& box, double t_s);

/// The outlines of every pose `box` takes in [0, end_s] other than the one it ends in.
std::vector<Segment> PastBoxOutlines(const sim::Box& box, double end_s);

/// Static walls, the doors closed at t_s and the boxes where they stand at t_s.
std::vector<Segment> WallsAt(const sim::World& world, double t_s);

/// Surfaces that stood at some time in [0, end_s] and not at end_s: doors closed during the
/// run and open at its end, and every earlier pose of a box that stands elsewhere at the end.
/// Empty when nothing in the world changed by end_s (then the map's present is its past).
std::vector<Segment> GoneSurfaces(const sim::World& world, double end_s);

/// The ground truth of a simulated run that ends at end_s: every surface that stood
/// (TrueWalls), those standing at the end, and those gone by then.
GroundTruth TruthOf(const sim::World& world, double end_s);

/// Writes the truth's segments as `prefix` + walls.tsv, and, when the world changed,
/// walls_now.tsv and gone.tsv (io/segments_file.hpp): a run's truth/ and a simulated log's
/// LOG-stem.truth.* files.
void WriteTruthWalls(const std::string& prefix, const GroundTruth& truth);
/// Reads what WriteTruthWalls wrote; nothing when `prefix` + walls.tsv does not exist.
std::optional<GroundTruth> ReadTruthWalls(const std::string& prefix);

}  // namespace lifelong::eval
