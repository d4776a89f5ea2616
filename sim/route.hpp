// Routes as a list of steps (drive to a point, stop for a while), expanded from a
// RouteConfig: back-and-forth repetitions, or a seeded random tour of places over the
// roadmap's shortest paths (Dijkstra), drawn from the route stream (sim/random_streams.hpp).
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

/// All steps of a back-and-forth or path route (they draw nothing).
std::vector<RouteStep> ExpandBackAndForth(const RouteConfig& route);

/// The next leg of a tour: draws destinations from `rng` (the route stream) until one is not
/// *current, appends the shortest roadmap path there and the stop, and moves *current to it.
/// Tours are expanded leg by leg as the robot needs them, never for the whole duration up
/// front, so a shorter tour draws the first legs of a longer one.
void AppendTourLeg(const RouteConfig& route, const World& world, int* current, std::mt19937_64* rng,
                   std::vector<RouteStep>* steps);

/// Rough time to drive the steps with the robot's limits, s.
double EstimateStepsDuration(const std::vector<RouteStep>& steps, const Point& start,
                             const RobotConfig& robot);

}  // namespace lifelong::sim
