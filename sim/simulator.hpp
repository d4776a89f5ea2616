// The simulator: steps a Box2D world at a fixed rate, drives the Pioneer along the route,
// integrates noisy wheel odometry and casts SICK laser scans. Deterministic, no wall clock:
// route choices, odometry noise and laser noise come from three independent streams
// derived from the scenario seed (sim/random_streams.hpp). A run depends on the seed and
// the simulated time only: the same scenario with a shorter tour duration (or fewer
// repetitions) yields the first part of the longer run's stream, bit for bit.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sensor/laser_scan.hpp"
#include "sensor/observation.hpp"
#include "sim/scenario.hpp"

namespace lifelong::sim {

/// The robot touched a wall, door or box (Box2D begin-contact); the robot is stopped by it,
/// not passed through.
struct Collision {
  double stamp_s = 0.0;
  std::string what;     ///< "wall", "door <name>" or "box <name>"
  Pose2 T_world_robot;  ///< true pose at the time
};

class Simulator {
 public:
  explicit Simulator(const Scenario& scenario);
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  /// Advances to the next laser scan; fills obs (stamp, T_odom_robot, scan with its mount,
  /// T_world_robot_true) and the ODOM messages since the previous scan (may be null).
  /// Returns false, filling nothing (odometry_since_last is cleared), once the route is
  /// finished: a tour at the first scan at or after its duration, a back-and-forth route
  /// at the last scan before the tick in which it runs out of steps (without braking to a
  /// standstill, which a longer route would not do), or at the time limit.
  bool Next(Observation* obs, std::vector<Odometry>* odometry_since_last);

  /// Stamp of the last observation returned, s (0 before the first).
  double time_s() const;
  /// Share of the route done, in [0, 1].
  double progress() const;
  const std::vector<Collision>& collisions() const;
  /// True when the run was cut at the time limit (2 x expected duration + 60 s) because
  /// the robot could not finish its route.
  bool timed_out() const;
  const Pose2& true_pose() const;

  /// A noise-free scan from the robot at an arbitrary pose in the current world state.
  LaserScan TrueScan(const Pose2& T_world_robot) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lifelong::sim
