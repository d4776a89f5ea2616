// Running the simulator to the end of a scenario, in memory, and writing what
// `lifelong simulate` writes: the CARMEN log, the true trajectory, the true map and a PNG.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "sensor/observation.hpp"
#include "sim/scenario.hpp"
#include "sim/simulator.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

struct SimulatedRun {
  std::vector<Observation> observations;
  std::vector<Odometry> odometry;  ///< ODOM messages, in time order
  std::vector<sim::Collision> collisions;
  bool timed_out = false;
  double duration_s = 0.0;
};

/// Simulates the whole scenario; progress lines go to `progress` when given.
SimulatedRun SimulateScenario(const sim::Scenario& scenario, std::ostream* progress);

/// The ground truth for map metrics: static walls, doors (as closed) and the boxes at each
/// pose they take.
std::vector<Segment> TrueWalls(const sim::World& world);

/// The time at which the first pass over the space ends: the first forth-and-back cycle of a
/// back-and-forth route; for a tour, the first time every destination has been visited (from
/// the true trajectory) or, failing that, a sixth of the run.
double FirstPassEnd(const sim::Scenario& scenario, const SimulatedRun& run);

/// Writes LOG (CARMEN, ODOM + ROBOTLASER1 + TRUEPOS), LOG-stem.truth.tum, LOG-stem.truth.pgm/.yaml
/// and LOG-stem.png (the world with the true and odometry trajectories).
void WriteSimulation(const std::string& log_path, const sim::Scenario& scenario,
                     const SimulatedRun& run, double resolution_m);

}  // namespace lifelong::eval
