#include "sim/route.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

#include "sensor/pose2.hpp"

namespace lifelong::sim {
namespace {

double Dist(const Point& a, const Point& b) { return std::hypot(b.x - a.x, b.y - a.y); }

void AppendStop(double stop_s, std::vector<RouteStep>* steps) {
  if (stop_s > 0.0) steps->push_back({RouteStep::Kind::kStop, {}, stop_s});
}

}  // namespace

std::vector<RouteStep> ExpandBackAndForth(const RouteConfig& route) {
  std::vector<RouteStep> steps;
  const auto& w = route.waypoints;
  for (int r = 0; r < route.repetitions; ++r) {
    for (std::size_t i = 1; i < w.size(); ++i) steps.push_back({RouteStep::Kind::kGoto, w[i], 0});
    AppendStop(route.stop_s, &steps);
    if (route.one_way) continue;
    for (std::size_t i = w.size() - 1; i-- > 0;) {
      steps.push_back({RouteStep::Kind::kGoto, w[i], 0});
    }
    AppendStop(route.stop_s, &steps);
  }
  return steps;
}

std::vector<int> ShortestPath(const World& world, int from, int to) {
  const std::size_t n = world.places.size();
  std::vector<std::vector<std::pair<int, double>>> adj(n);
  for (const auto& [a, b] : world.roadmap) {
    const double d = Dist(world.places[a].at, world.places[b].at);
    adj[a].emplace_back(b, d);
    adj[b].emplace_back(a, d);
  }
  std::vector<double> cost(n, std::numeric_limits<double>::infinity());
  std::vector<int> prev(n, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  cost[from] = 0.0;
  open.emplace(0.0, from);
  while (!open.empty()) {
    const auto [c, u] = open.top();
    open.pop();
    if (c > cost[u]) continue;
    for (const auto& [v, d] : adj[u]) {
      if (c + d < cost[v]) {
        cost[v] = c + d;
        prev[v] = u;
        open.emplace(cost[v], v);
      }
    }
  }
  if (!std::isfinite(cost[to])) return {};
  std::vector<int> path;
  for (int v = to; v != -1; v = prev[v]) path.push_back(v);
  std::reverse(path.begin(), path.end());
  return path;
}

Point RouteStart(const RouteConfig& route, const World& world) {
  if (route.kind == RouteConfig::Kind::kTour) return world.places.at(route.start_place).at;
  return route.waypoints.at(0);
}

void AppendTourLeg(const RouteConfig& route, const World& world, int* current, std::mt19937_64* rng,
                   std::vector<RouteStep>* steps) {
  const std::size_t n = route.tour_places.size();
  if (n == 0) return;
  int dest = *current;
  // The scenario loader ensures a place other than the start; the guard keeps a tour built
  // in code without one from spinning forever (the robot then stays put).
  for (int guard = 0; dest == *current && guard < 1000000; ++guard) {
    dest = route.tour_places[(*rng)() % n];
  }
  if (dest == *current) return;
  const std::vector<int> path = ShortestPath(world, *current, dest);
  for (std::size_t i = 1; i < path.size(); ++i) {
    steps->push_back({RouteStep::Kind::kGoto, world.places[path[i]].at, 0.0});
  }
  AppendStop(route.stop_s, steps);
  *current = dest;
}

double EstimateStepsDuration(const std::vector<RouteStep>& steps, const Point& start,
                             const RobotConfig& robot) {
  double t = 0.0, heading = 0.0;
  Point at = start;
  bool first = true;
  for (const RouteStep& s : steps) {
    if (s.kind == RouteStep::Kind::kStop) {
      t += s.stop_s;
      continue;
    }
    const double d = Dist(at, s.target);
    if (d < 1e-9) continue;
    const double h = std::atan2(s.target.y - at.y, s.target.x - at.x);
    if (!first) t += std::abs(NormalizeAngle(h - heading)) / robot.max_turn_rate_radps;
    t += d / robot.max_speed_mps + robot.max_speed_mps / robot.max_accel_mps2;
    heading = h;
    at = s.target;
    first = false;
  }
  return t;
}

}  // namespace lifelong::sim
