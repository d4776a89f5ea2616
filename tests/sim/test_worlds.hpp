// Tiny scenes shared by the sim tests, built in code so the answers can be worked out by hand.
#pragma once

#include <vector>

#include "sim/scenario.hpp"

namespace lifelong::sim::testing {

/// A scenario in `world` driving the waypoints once (no way back), no noise at all,
/// laser 5 Hz with 181 beams at the robot centre.
inline Scenario OneWay(const World& world, std::vector<Point> waypoints) {
  Scenario s;
  s.name = "test";
  s.world = world;
  s.route.kind = RouteConfig::Kind::kBackAndForth;
  s.route.one_way = true;
  s.route.waypoints = std::move(waypoints);
  s.laser.T_robot_laser = Pose2();
  s.laser.range_noise_m = 0.0;
  s.odometry.slip_variance_m2_per_m = 0.0;
  s.odometry.left_scale = s.odometry.right_scale = s.odometry.track_scale = 1.0;
  EstimateDuration(&s);
  return s;
}

/// A world with one straight wall from (x, -h) to (x, h).
inline World WallAt(double x, double h) {
  World w;
  w.walls.push_back({{{x, -h}, {x, h}}, false});
  return w;
}

}  // namespace lifelong::sim::testing
