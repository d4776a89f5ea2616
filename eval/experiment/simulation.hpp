// Running the simulator to the end of a scenario, in memory, and writing what
// `lifelong simulate` writes: the CARMEN log, the true trajectory, the true map and a PNG.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "eval/metrics/summary.hpp"
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

/// Simulates the whole scenario; progress goes to `progress` when given (`terminal`: one
/// line redrawn in 1 % steps; else a plain line per 10 %). Throws Interrupted after Ctrl-C.
SimulatedRun SimulateScenario(const sim::Scenario& scenario, std::ostream* progress,
                              bool terminal = false);

/// The run's outcome for summary.json's "simulation" (collisions, timeout, durations).
SimulationOutcome Outcome(const sim::Scenario& scenario, const SimulatedRun& run);

/// The outcome as lines for a person: "collision at t = ... with ...", a timeout with both
/// durations; empty when the robot drove its route untouched.
std::string OutcomeText(const SimulationOutcome& outcome);

/// The time at which the first pass over the space ends: the first forth-and-back cycle of a
/// back-and-forth route; for a tour, the first time every destination has been visited (from
/// the true trajectory). Absent when a tour never visits every destination: the run then has
/// no first pass, and nodes_after_first_pass / first_pass_mean are left out of the summary.
std::optional<double> FirstPassEnd(const sim::Scenario& scenario, const SimulatedRun& run);

/// Throws InputError naming the world file when a raster of the world at resolution_m (the
/// truth map, the figures) would exceed kMaxRasterCells: before the simulation, not after.
void CheckWorldRaster(const sim::Scenario& scenario, double resolution_m);

/// Writes LOG (CARMEN, ODOM + ROBOTLASER1 + TRUEPOS), LOG-stem.truth.tum, LOG-stem.truth.pgm/.yaml
/// and LOG-stem.png (the world with the true and odometry trajectories).
void WriteSimulation(const std::string& log_path, const sim::Scenario& scenario,
                     const SimulatedRun& run, double resolution_m);

}  // namespace lifelong::eval
