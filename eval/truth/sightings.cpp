// What the robot saw of a changing object after its last change (sightings.hpp).
#include "eval/truth/sightings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/geometry.hpp"

namespace lifelong::eval {
namespace {

constexpr double kSeenM = 0.1;   // a return this close to a present segment hits it
constexpr double kShortM = 0.1;  // a beam is free up to this short of its return
constexpr double kPi = 3.14159265358979323846;

double Wrap(double a) { return a - 2.0 * kPi * std::floor((a + kPi) / (2.0 * kPi)); }

struct Bounds {
  double x0 = std::numeric_limits<double>::max(), y0 = x0;
  double x1 = std::numeric_limits<double>::lowest(), y1 = x1;
  void Add(const std::vector<Segment>& segments, double margin) {
    for (const Segment& s : segments) {
      x0 = std::min({x0, s.x0 - margin, s.x1 - margin});
      y0 = std::min({y0, s.y0 - margin, s.y1 - margin});
      x1 = std::max({x1, s.x0 + margin, s.x1 + margin});
      y1 = std::max({y1, s.y0 + margin, s.y1 + margin});
    }
  }
  bool Contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

/// The part [*t0, *t1] of the ray (ox, oy) + t (ux, uy), t in [0, len], inside b (Liang and
/// Barsky's clipping); false when the ray misses b.
bool Clip(const Bounds& b, double ox, double oy, double ux, double uy, double len, double* t0,
          double* t1) {
  double lo = 0.0, hi = len;
  const auto edge = [&](double p, double q) {  // the half-plane p t <= q
    if (std::abs(p) < 1e-12) return q >= 0.0;
    const double r = q / p;
    (p < 0.0 ? lo : hi) = p < 0.0 ? std::max(lo, r) : std::min(hi, r);
    return lo <= hi;
  };
  if (!edge(-ux, ox - b.x0) || !edge(ux, b.x1 - ox) || !edge(-uy, oy - b.y0) ||
      !edge(uy, b.y1 - oy)) {
    return false;
  }
  *t0 = lo;
  *t1 = hi;
  return true;
}

/// The bearings (world frame) under which `b` lies from (x, y): [*lo, *hi] about *mid;
/// false when (x, y) lies inside b (every bearing).
bool Span(const Bounds& b, double x, double y, double* mid, double* lo, double* hi) {
  if (b.Contains(x, y)) return false;
  *mid = std::atan2(0.5 * (b.y0 + b.y1) - y, 0.5 * (b.x0 + b.x1) - x);
  *lo = 0.0, *hi = 0.0;
  for (const double cx : {b.x0, b.x1}) {
    for (const double cy : {b.y0, b.y1}) {
      const double d = Wrap(std::atan2(cy - y, cx - x) - *mid);
      *lo = std::min(*lo, d), *hi = std::max(*hi, d);
    }
  }
  return true;
}

}  // namespace

std::int64_t CellSet::Key(double x, double y) const {
  const auto ix = static_cast<std::int64_t>(std::floor(x / cell_m_));
  const auto iy = static_cast<std::int64_t>(std::floor(y / cell_m_));
  return (ix << 32) ^ (iy & 0xffffffffLL);
}

bool CellSet::Near(double x, double y) const {
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      if (cells_.count(Key(x + dx * cell_m_, y + dy * cell_m_))) return true;
    }
  }
  return false;
}

Sightings CollectSightings(const std::vector<Observation>& stream, std::size_t scans,
                           double since_s, const std::vector<Segment>& present,
                           const std::vector<Segment>& past, double cell_m) {
  Sightings out(cell_m);
  // The cells about the past outlines, where a free beam shows the place left.
  CellSet near_past(cell_m);
  for (const Segment& s : past) {
    const double len = std::hypot(s.x1 - s.x0, s.y1 - s.y0);
    const int steps = static_cast<int>(std::ceil(len / (0.5 * cell_m))) + 1;
    for (int i = 0; i <= steps; ++i) {
      const double f = static_cast<double>(i) / steps;
      near_past.Add(s.x0 + f * (s.x1 - s.x0), s.y0 + f * (s.y1 - s.y0));
    }
  }
  Bounds all, past_box;
  all.Add(present, kSeenM);
  all.Add(past, cell_m);
  past_box.Add(past, cell_m);
  const std::size_t n = std::min(scans, stream.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Observation& o = stream[i];
    if (!o.T_world_robot_true || o.stamp_s < since_s) continue;
    const LaserScan& scan = o.scan;
    const Pose2 T = *o.T_world_robot_true * scan.T_robot_laser;
    double mid = 0.0, lo = 0.0, hi = 0.0;
    const bool spanned = Span(all, T.x, T.y, &mid, &lo, &hi);
    const double slack = std::abs(scan.angle_increment_rad);
    bool saw = false;
    for (std::size_t k = 0; k < scan.ranges_m.size(); ++k) {
      if (scan.ranges_m[k] <= 0.0f) continue;
      const double a = T.theta + scan.Bearing(k);
      if (spanned) {
        const double d = Wrap(a - mid);
        if (d < lo - slack || d > hi + slack) continue;
      }
      const bool hit = scan.IsReturn(k);
      const double r = hit ? scan.ranges_m[k] : scan.range_max_m;
      const double ux = std::cos(a), uy = std::sin(a);
      const sim::Point end{T.x + r * ux, T.y + r * uy};
      if (hit && std::any_of(present.begin(), present.end(), [&](const Segment& s) {
            return sim::PointSegmentDistance(end, s) <= kSeenM;
          })) {
        out.hit.Add(end.x, end.y);
        saw = true;
      }
      double t0 = 0.0, t1 = 0.0;
      const double free_len = hit ? r - kShortM : r;
      if (past.empty() || free_len <= 0.0 || !Clip(past_box, T.x, T.y, ux, uy, free_len, &t0, &t1))
        continue;
      for (double t = t0; t <= t1; t += 0.5 * cell_m) {
        const double x = T.x + t * ux, y = T.y + t * uy;
        if (!near_past.Near(x, y)) continue;
        out.freed.Add(x, y);
        saw = true;
      }
    }
    if (saw) out.last_s = std::max(out.last_s.value_or(o.stamp_s), o.stamp_s);
  }
  return out;
}

}  // namespace lifelong::eval
