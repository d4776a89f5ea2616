// A line segment in a world frame, metres: true walls (sim, eval), laser rays and drawn
// graph edges (render).
#pragma once

namespace lifelong {

/// The segment from (x0, y0) to (x1, y1), metres.
struct Segment {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
};

}  // namespace lifelong
