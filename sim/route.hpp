// Routes as a list of steps (drive to a point, stop for a while), expanded from a
// RouteConfig: back-and-forth repetitions, or a seeded random tour of places over the
// roadmap's shortest paths (Dijkstra).
#pragma once

#include <random>
#include <vector>

#include "sim/scenario.hpp"

namespace lifelong::sim {

struct RouteStep {
  enum class Kind { kGoto, kStop };
  Kind kind = Kind::kGoto;
  Point target;         ///< kGoto: where to drive, m
  double stop_s = 0.0;  ///< kStop: how long to stand still, s
};

/// Place indices along the shortest roadmap path from -> to (both included); empty when
/// unreachable.
std::vector<int> ShortestPath(const World& world, int from, int to);

/// Start point of the route.
Point RouteStart(const RouteConfig& route, const World& world);

/// Expands the route. Tours draw destinations from `rng` until the path is long enough to
/// fill route.tour_duration_s at `speed_mps`, with margin.
std::vector<RouteStep> ExpandRoute(const RouteConfig& route, const World& world, double speed_mps,
                                   std::mt19937_64* rng);

/// Rough time to drive the steps with the robot's limits, s.
double EstimateStepsDuration(const std::vector<RouteStep>& steps, const Point& start,
                             const RobotConfig& robot);

}  // namespace lifelong::sim
