#include "sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lifelong::sim {
namespace {

std::vector<Point> BoxCorners(const Point& c, double w, double h, double yaw) {
  const double cs = std::cos(yaw), sn = std::sin(yaw);
  std::vector<Point> out;
  for (const auto& [u, v] : {std::pair{-w, -h}, {w, -h}, {w, h}, {-w, h}}) {
    out.push_back({c.x + 0.5 * (cs * u - sn * v), c.y + 0.5 * (sn * u + cs * v)});
  }
  return out;
}

}  // namespace

bool Door::IsClosed(double t_s) const {
  return std::any_of(closed_intervals_s.begin(), closed_intervals_s.end(),
                     [t_s](const auto& iv) { return iv.first <= t_s && t_s < iv.second; });
}

int World::FindPlace(const std::string& name) const {
  for (std::size_t i = 0; i < places.size(); ++i) {
    if (places[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::vector<Segment> WallSegments(const World& world) {
  std::vector<Segment> out;
  for (const Wall& w : world.walls) {
    const std::vector<Segment> s = ToSegments(w.points, w.closed);
    out.insert(out.end(), s.begin(), s.end());
  }
  return out;
}

std::vector<Segment> DoorSegments(const World& world) {
  std::vector<Segment> out;
  for (const Door& d : world.doors) out.push_back(d.segment);
  return out;
}

std::vector<Segment> BoxSegments(const World& world) {
  std::vector<Segment> out;
  for (const Box& b : world.boxes) {
    const auto s = ToSegments(BoxCorners(b.center, b.width_m, b.height_m, b.yaw_rad), true);
    out.insert(out.end(), s.begin(), s.end());
  }
  return out;
}

double ClearanceAt(const World& world, const Point& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& segs : {WallSegments(world), DoorSegments(world), BoxSegments(world)}) {
    for (const Segment& s : segs) best = std::min(best, PointSegmentDistance(p, s));
  }
  return best;
}

double PathClearance(const World& world, const Segment& path) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& segs : {WallSegments(world), BoxSegments(world)}) {
    for (const Segment& s : segs) best = std::min(best, SegmentSegmentDistance(path, s));
  }
  return best;
}

bool InsideObstacle(const World& world, const Point& p) {
  for (const Wall& w : world.walls) {
    if (w.closed && PointInPolygon(p, w.points)) return true;
  }
  for (const Box& b : world.boxes) {
    if (PointInPolygon(p, BoxCorners(b.center, b.width_m, b.height_m, b.yaw_rad))) return true;
  }
  return false;
}

std::string CheckFree(const World& world, const Point& p, double clearance_m) {
  if (InsideObstacle(world, p)) return "lies inside a wall polygon or a box";
  const double c = ClearanceAt(world, p);
  if (c < clearance_m) {
    return "is " + std::to_string(c) + " m from a wall, closer than the clearance " +
           std::to_string(clearance_m) + " m";
  }
  return "";
}

std::string CheckPath(const World& world, const Point& a, const Point& b, double clearance_m) {
  const double c = PathClearance(world, {a.x, a.y, b.x, b.y});
  if (c <= 0.0) return "crosses a wall";
  if (c < clearance_m) {
    return "passes " + std::to_string(c) + " m from a wall, closer than the clearance " +
           std::to_string(clearance_m) + " m";
  }
  return "";
}

}  // namespace lifelong::sim
