// Plane geometry for world validation: points, segments, polygon tests. Metres.
#pragma once

#include <vector>

#include "types/segment.hpp"

namespace lifelong::sim {

struct Point {
  double x = 0.0;  ///< m
  double y = 0.0;  ///< m
};

/// True when the closed segments a and b share at least one point.
bool SegmentsIntersect(const Segment& a, const Segment& b);

/// Euclidean distance from p to the closed segment s.
double PointSegmentDistance(const Point& p, const Segment& s);

/// Smallest distance between two segments (0 when they intersect).
double SegmentSegmentDistance(const Segment& a, const Segment& b);

/// Even-odd rule; `ring` is a closed polygon given without repeating the first vertex.
bool PointInPolygon(const Point& p, const std::vector<Point>& ring);

/// True when two non-adjacent edges of the closed polygon `ring` touch.
bool PolygonSelfIntersects(const std::vector<Point>& ring);

/// Segments of a polyline, or of a polygon when `closed` (last vertex joined to the first).
std::vector<Segment> ToSegments(const std::vector<Point>& points, bool closed);

}  // namespace lifelong::sim
