// Hand-made 2D worlds of line segments and an exact ray caster, for the grid-map and
// matcher tests and the front-end benchmark. A rectangle is its four edges, so a beam's range
// is the analytic ray-rectangle intersection.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "types/segment.hpp"

namespace lifelong::testing {

using World = std::vector<Segment>;

inline void AddRectangle(double x0, double y0, double x1, double y1, World* w) {
  const Eigen::Vector2d p[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d& q = p[(i + 1) % 4];
    w->push_back({p[i].x(), p[i].y(), q.x(), q.y()});
  }
}

/// An 8 m x 5 m room, lower-left corner at the origin, with two boxes.
inline World RoomWorld() {
  World w;
  AddRectangle(0.0, 0.0, 8.0, 5.0, &w);
  AddRectangle(2.0, 1.0, 2.6, 1.8, &w);
  AddRectangle(5.5, 3.2, 6.5, 4.0, &w);
  return w;
}

/// A featureless corridor along x: walls at y = 0 and y = 2, 200 m long.
inline World CorridorWorld() { return {{-100.0, 0.0, 100.0, 0.0}, {-100.0, 2.0, 100.0, 2.0}}; }

/// A lattice of 0.2 m posts, unrelated to the room.
inline World PostsWorld() {
  World w;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 4; ++j) AddRectangle(1.3 * i, 1.1 * j, 1.3 * i + 0.2, 1.1 * j + 0.2, &w);
  }
  return w;
}

/// Distance along the ray o + t d (|d| = 1) to the nearest segment, or +inf.
inline double CastRay(const World& w, const Eigen::Vector2d& o, const Eigen::Vector2d& d) {
  auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : w) {
    const Eigen::Vector2d a(s.x0, s.y0), b(s.x1, s.y1);
    const Eigen::Vector2d e = b - a;
    const double den = cross(d, e);
    if (std::abs(den) < 1e-12) continue;
    const double t = cross(a - o, e) / den, u = cross(a - o, d) / den;
    if (t > 1e-9 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
  }
  return best;
}

/// A noise-free scan of `beams` beams over [-fov/2, fov/2] from T_world_robot (laser at the
/// robot origin). Beams hitting nothing within range_max_m read range_max_m ("no return").
inline LaserScan SimulateScan(const World& w, const Pose2& T_world_robot, int beams = 181,
                              double fov_rad = 3.14159265358979323846, double range_max_m = 30.0) {
  LaserScan scan;
  scan.angle_min_rad = -fov_rad / 2.0;
  scan.angle_increment_rad = fov_rad / (beams - 1);
  scan.range_max_m = range_max_m;
  for (int i = 0; i < beams; ++i) {
    const double a = T_world_robot.theta + scan.Bearing(static_cast<std::size_t>(i));
    const double r = CastRay(w, {T_world_robot.x, T_world_robot.y}, {std::cos(a), std::sin(a)});
    scan.ranges_m.push_back(static_cast<float>(std::min(r, range_max_m)));
  }
  return scan;
}

}  // namespace lifelong::testing
