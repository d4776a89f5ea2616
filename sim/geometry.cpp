#include "sim/geometry.hpp"

#include <algorithm>
#include <cmath>

namespace lifelong::sim {
namespace {

double Cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Sign of the turn o -> a -> b: +1 left, -1 right, 0 collinear (within 1e-12 m^2).
int Orientation(double ox, double oy, double ax, double ay, double bx, double by) {
  const double c = Cross(ax - ox, ay - oy, bx - ox, by - oy);
  if (std::abs(c) < 1e-12) return 0;
  return c > 0.0 ? 1 : -1;
}

bool OnSegment(double px, double py, const Segment& s) {
  return std::min(s.x0, s.x1) - 1e-12 <= px && px <= std::max(s.x0, s.x1) + 1e-12 &&
         std::min(s.y0, s.y1) - 1e-12 <= py && py <= std::max(s.y0, s.y1) + 1e-12;
}

}  // namespace

bool SegmentsIntersect(const Segment& a, const Segment& b) {
  const int o1 = Orientation(a.x0, a.y0, a.x1, a.y1, b.x0, b.y0);
  const int o2 = Orientation(a.x0, a.y0, a.x1, a.y1, b.x1, b.y1);
  const int o3 = Orientation(b.x0, b.y0, b.x1, b.y1, a.x0, a.y0);
  const int o4 = Orientation(b.x0, b.y0, b.x1, b.y1, a.x1, a.y1);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && OnSegment(b.x0, b.y0, a)) return true;
  if (o2 == 0 && OnSegment(b.x1, b.y1, a)) return true;
  if (o3 == 0 && OnSegment(a.x0, a.y0, b)) return true;
  if (o4 == 0 && OnSegment(a.x1, a.y1, b)) return true;
  return false;
}

double PointSegmentDistance(const Point& p, const Segment& s) {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? ((p.x - s.x0) * dx + (p.y - s.y0) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (s.x0 + t * dx), p.y - (s.y0 + t * dy));
}

double SegmentSegmentDistance(const Segment& a, const Segment& b) {
  if (SegmentsIntersect(a, b)) return 0.0;
  return std::min({PointSegmentDistance({a.x0, a.y0}, b), PointSegmentDistance({a.x1, a.y1}, b),
                   PointSegmentDistance({b.x0, b.y0}, a), PointSegmentDistance({b.x1, b.y1}, a)});
}

bool PointInPolygon(const Point& p, const std::vector<Point>& ring) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const Point& a = ring[i];
    const Point& b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
      inside = !inside;
    }
  }
  return inside;
}

bool PolygonSelfIntersects(const std::vector<Point>& ring) {
  const std::vector<Segment> edges = ToSegments(ring, true);
  const std::size_t n = edges.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = (j == i + 1) || (i == 0 && j == n - 1);
      if (!adjacent && SegmentsIntersect(edges[i], edges[j])) return true;
    }
  }
  return false;
}

std::vector<Segment> ToSegments(const std::vector<Point>& points, bool closed) {
  std::vector<Segment> out;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    out.push_back({points[i].x, points[i].y, points[i + 1].x, points[i + 1].y});
  }
  if (closed && points.size() > 2) {
    out.push_back({points.back().x, points.back().y, points.front().x, points.front().y});
  }
  return out;
}

}  // namespace lifelong::sim
