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

namespace {

Bounds OrDefault(const Bounds& b) { return b.Empty() ? Bounds{-1.0, -1.0, 1.0, 1.0} : b; }

Bounds PanelBounds(const Panel& p) {
  Bounds b;
  if (p.map.width > 0 && p.map.height > 0) {
    b.Extend(p.map.origin_x_m, p.map.origin_y_m);
    b.Extend(p.map.origin_x_m + p.map.width * p.map.resolution_m,
             p.map.origin_y_m + p.map.height * p.map.resolution_m);
  }
  for (const Pose2& n : p.nodes) b.Extend(n.x, n.y);
  b.Extend(p.robot_estimate.x, p.robot_estimate.y);
  return b;
}

}  // namespace

std::vector<Bounds> ViewBounds(const Scene& scene) {
  Bounds world;
  for (const Segment& s : scene.walls) world.Extend(s.x0, s.y0), world.Extend(s.x1, s.y1);
  for (const Segment& s : scene.rays) world.Extend(s.x0, s.y0), world.Extend(s.x1, s.y1);
  world.Extend(scene.robot_true.x, scene.robot_true.y);
  std::vector<Bounds> out{OrDefault(world)};
  for (const Panel& p : scene.panels) out.push_back(OrDefault(PanelBounds(p)));
  return out;
}

}  // namespace lifelong::render
