#include "render/scene.hpp"

#include <algorithm>

namespace lifelong::render {

void Bounds::Extend(double x, double y) {
  if (Empty()) {
    min_x = max_x = x;
    min_y = max_y = y;
    return;
  }
  min_x = std::min(min_x, x), max_x = std::max(max_x, x);
  min_y = std::min(min_y, y), max_y = std::max(max_y, y);
}

void Bounds::Extend(const Bounds& other) {
  if (other.Empty()) return;
  Extend(other.min_x, other.min_y);
  Extend(other.max_x, other.max_y);
}

Bounds SceneBounds(const Scene& scene) {
  Bounds b;
  for (const Segment& s : scene.walls) b.Extend(s.x0, s.y0), b.Extend(s.x1, s.y1);
  for (const Segment& s : scene.rays) b.Extend(s.x0, s.y0), b.Extend(s.x1, s.y1);
  b.Extend(scene.robot_true.x, scene.robot_true.y);
  for (const Panel& p : scene.panels) {
    if (p.map.width > 0 && p.map.height > 0) {
      b.Extend(p.map.origin_x_m, p.map.origin_y_m);
      b.Extend(p.map.origin_x_m + p.map.width * p.map.resolution_m,
               p.map.origin_y_m + p.map.height * p.map.resolution_m);
    }
    for (const Pose2& n : p.nodes) b.Extend(n.x, n.y);
    b.Extend(p.robot_estimate.x, p.robot_estimate.y);
  }
  return b;
}

}  // namespace lifelong::render
