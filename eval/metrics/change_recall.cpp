#include "eval/metrics/change_recall.hpp"

#include <algorithm>
#include <cmath>

#include "eval/metrics/map_quality.hpp"
#include "eval/truth/sightings.hpp"
#include "eval/truth/world_state.hpp"

namespace lifelong::eval {
namespace {

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

// When the object last changed at or before end_s: a door's last opening or closing, a
// box's last move; 0 when it stands as it did at the start.
double LastChange(const Object& o, double end_s) {
  double last = 0.0;
  if (o.door) {
    for (const auto& [begin, end] : o.door->closed_intervals_s) {
      if (begin > 0.0 && begin <= end_s) last = std::max(last, begin);
      if (end <= end_s) last = std::max(last, end);
    }
  } else {
    for (const sim::BoxMove& m : o.box->moves) {
      if (m.t_s <= end_s) last = std::max(last, m.t_s);
    }
  }
  return last;
}

/// The object's present and past outlines at end_s, and what stands then besides its
/// present.
struct Outlines {
  std::vector<Segment> present, past, others;
};

Outlines OutlinesOf(const Object& o, double end_s, const std::vector<Segment>& now) {
  Outlines out;
  if (o.door) {
    (o.door->IsClosed(end_s) ? out.present : out.past).push_back(o.door->segment);
  } else {
    out.present = BoxOutlineAt(*o.box, end_s);
    out.past = PastBoxOutlines(*o.box, end_s);
  }
  for (const Segment& s : now) {
    if (std::find_if(out.present.begin(), out.present.end(), [&](const Segment& q) {
          return q.x0 == s.x0 && q.y0 == s.y0 && q.x1 == s.x1 && q.y1 == s.y1;
        }) == out.present.end()) {
      out.others.push_back(s);
    }
  }
  return out;
}

}  // namespace

std::optional<ChangeRecall> ComputeChangeRecall(const sim::World& world, double end_s,
                                                const std::vector<Observation>& stream,
                                                const OccupancyGrid& map, const Pose2& T_truth_est,
                                                std::size_t scans, const TruthRaster* raster) {
  std::vector<Object> objects;
  for (const sim::Door& d : world.doors) objects.push_back({"door " + d.name, &d, nullptr});
  for (const sim::Box& b : world.boxes) objects.push_back({"box " + b.name, nullptr, &b});
  const std::vector<Segment> now = WallsAt(world, end_s);
  ChangeRecall out;
  std::vector<Sightings> sightings;  // every changed object's, for stale_seen
  int shown_recent = 0;
  for (const Object& o : objects) {
    if (!Changed(o, end_s)) continue;
    ObjectPresent p;
    // Its present and its past, each against the rest of what stands at the end.
    const Outlines lines = OutlinesOf(o, end_s, now);
    // Judged on what the robot saw after the change: the present cells a return hit, the
    // past cells a beam crossed.
    const Sightings& seen = sightings.emplace_back(CollectSightings(
        stream, scans, LastChange(o, end_s), lines.present, lines.past, map.resolution_m));
    if (seen.last_s) p.since_seen_s = std::max(0.0, end_s - *seen.last_s);
    const auto hit = [&](double x, double y) { return seen.hit.Near(x, y); };
    const auto freed = [&](double x, double y) { return seen.freed.Near(x, y); };
    const ShownCells now_cells = CountShown(map, lines.present, lines.others, T_truth_est, {}, hit);
    const ShownCells past_cells = CountShown(map, lines.past, now, T_truth_est, {}, freed);
    const std::optional<double> shown_now = now_cells.Share();
    const std::optional<double> shown_past = past_cells.Share();
    if (seen.last_s) {
      p.shows_present = shown_now.value_or(1.0) >= 0.5 && shown_past.value_or(0.0) < 0.5;
      p.present_shown = shown_now;
      p.past_shown = shown_past;
      p.present_seen_cells = static_cast<std::int64_t>(now_cells.counted);
      p.past_seen_cells = static_cast<std::int64_t>(past_cells.counted);
    }
    p.present = lines.present;
    p.past = lines.past;
    if (p.since_seen_s && *p.since_seen_s <= kRecentS) {
      ++out.recent;
      shown_recent += *p.shows_present ? 1 : 0;
    }
    out.objects[o.name] = p;
  }
  if (out.objects.empty()) return std::nullopt;
  if (out.recent > 0) out.recall = static_cast<double>(shown_recent) / out.recent;
  if (raster && raster->Fits(map)) {
    out.stale_seen = StaleShare(map, *raster, T_truth_est, {}, [&](double x, double y) {
      return std::any_of(sightings.begin(), sightings.end(),
                         [&](const Sightings& s) { return s.freed.Near(x, y); });
    });
  }
  return out;
}

}  // namespace lifelong::eval
