#include "eval/metrics/change_recall.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "eval/metrics/map_quality.hpp"
#include "eval/metrics/world_state.hpp"
#include "sim/geometry.hpp"

namespace lifelong::eval {
namespace {

constexpr double kSeenM = 0.1;      // a return this close to an object saw it
constexpr double kRecentS = 600.0;  // change_recall counts objects seen this recently

struct Object {
  std::string name;
  const sim::Door* door = nullptr;
  const sim::Box* box = nullptr;
};

bool Changed(const Object& o, double end_s) {
  if (o.door)
    return o.door->IsClosed(0.0) != o.door->IsClosed(end_s) ||
           std::any_of(o.door->closed_intervals_s.begin(), o.door->closed_intervals_s.end(),
                       [&](const auto& iv) { return iv.first > 0.0 && iv.first <= end_s; });
  return std::any_of(o.box->moves.begin(), o.box->moves.end(),
                     [&](const sim::BoxMove& m) { return m.t_s <= end_s; });
}

// The last stamp at which one of the first `scans` scans saw the object.
std::optional<double> LastSeen(const Object& o, const std::vector<Observation>& stream,
                               std::size_t scans) {
  const auto end = stream.begin() + static_cast<std::ptrdiff_t>(std::min(scans, stream.size()));
  for (auto it = std::make_reverse_iterator(end); it != stream.rend(); ++it) {
    if (!it->T_world_robot_true) continue;
    const double t = it->stamp_s;
    const LaserScan& scan = it->scan;
    const Pose2 T = *it->T_world_robot_true * scan.T_robot_laser;
    const bool open_door = o.door && !o.door->IsClosed(t);
    const std::vector<Segment> shape =
        o.door ? std::vector<Segment>{o.door->segment} : BoxOutlineAt(*o.box, t);
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      const bool hit = scan.IsReturn(i);
      const double r = hit ? scan.ranges_m[i] : scan.range_max_m;
      double x = 0.0, y = 0.0;
      T.Apply(r * std::cos(scan.Bearing(i)), r * std::sin(scan.Bearing(i)), &x, &y);
      if (open_door) {
        if (sim::SegmentsIntersect({T.x, T.y, x, y}, shape[0])) return t;
      } else if (hit) {
        for (const Segment& s : shape) {
          if (sim::PointSegmentDistance({x, y}, s) <= kSeenM) return t;
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<ChangeRecall> ComputeChangeRecall(const sim::World& world, double end_s,
                                                const std::vector<Observation>& stream,
                                                const OccupancyGrid& map, const Pose2& T_truth_est,
                                                std::size_t scans) {
  std::vector<Object> objects;
  for (const sim::Door& d : world.doors) objects.push_back({"door " + d.name, &d, nullptr});
  for (const sim::Box& b : world.boxes) objects.push_back({"box " + b.name, nullptr, &b});
  const std::vector<Segment> now = WallsAt(world, end_s);
  ChangeRecall out;
  int shown_recent = 0;
  for (const Object& o : objects) {
    if (!Changed(o, end_s)) continue;
    ObjectPresent p;
    const std::optional<double> seen = LastSeen(o, stream, scans);
    if (seen) p.since_seen_s = std::max(0.0, end_s - *seen);
    // Its present and its past, each against the rest of what stands at the end.
    std::vector<Segment> present, past;
    if (o.door) {
      (o.door->IsClosed(end_s) ? present : past).push_back(o.door->segment);
    } else {
      present = BoxOutlineAt(*o.box, end_s);
      past = PastBoxOutlines(*o.box, end_s);
    }
    std::vector<Segment> others;
    for (const Segment& s : now) {
      if (std::find_if(present.begin(), present.end(), [&](const Segment& q) {
            return q.x0 == s.x0 && q.y0 == s.y0 && q.x1 == s.x1 && q.y1 == s.y1;
          }) == present.end()) {
        others.push_back(s);
      }
    }
    const std::optional<double> shown_now = present.empty()
                                                ? std::optional<double>(1.0)
                                                : ShownShare(map, present, others, T_truth_est);
    const std::optional<double> shown_past =
        past.empty() ? std::optional<double>(0.0) : ShownShare(map, past, now, T_truth_est);
    p.shows_present = shown_now.value_or(1.0) >= 0.5 && shown_past.value_or(0.0) < 0.5;
    p.present = present;
    p.past = past;
    if (p.since_seen_s && *p.since_seen_s <= kRecentS) {
      ++out.recent;
      shown_recent += p.shows_present ? 1 : 0;
    }
    out.objects[o.name] = p;
  }
  if (out.objects.empty()) return std::nullopt;
  if (out.recent > 0) out.recall = static_cast<double>(shown_recent) / out.recent;
  return out;
}

}  // namespace lifelong::eval
