// Scan-to-scan change detection (change_detection.hpp).
#include "slam/grid/change_detection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>

#include <Eigen/Core>

#include "slam/grid/change_runs.hpp"

namespace lifelong::slam {
namespace {

using change_runs::KeepRuns;
using change_runs::KeepRunsToTheEdge;

constexpr double kTwoPi = 6.283185307179586;

/// A pose's rotation computed once: Apply gives what Pose2::Apply gives, bit for bit,
/// without a cosine and a sine per point.
struct Frame {
  explicit Frame(const Pose2& T) : x(T.x), y(T.y), c(std::cos(T.theta)), s(std::sin(T.theta)) {}
  void Apply(double px, double py, double* out_x, double* out_y) const {
    *out_x = x + c * px - s * py;
    *out_y = y + s * px + c * py;
  }
  double x, y, c, s;
};

/// cos and sin of each beam's bearing, for scans of this geometry (one laser's, so computed
/// once a run); the same values as computing them per beam.
const std::vector<std::array<double, 2>>& Directions(const LaserScan& scan) {
  thread_local double angle_min = 0.0, increment = 0.0;
  thread_local std::vector<std::array<double, 2>> table;
  if (table.size() != scan.ranges_m.size() || angle_min != scan.angle_min_rad ||
      increment != scan.angle_increment_rad) {
    angle_min = scan.angle_min_rad;
    increment = scan.angle_increment_rad;
    table.resize(scan.ranges_m.size());
    for (std::size_t i = 0; i < table.size(); ++i) {
      table[i] = {std::cos(scan.Bearing(i)), std::sin(scan.Bearing(i))};
    }
  }
  return table;
}

/// Where a return of one scan falls in another: the beam at its bearing and its distance
/// from that scan's laser; beam < 0 when it is outside the field of view or too close.
struct Seen {
  long beam = -1;
  double distance_m = 0.0;
  double x = 0.0, y = 0.0;  ///< in that scan's laser frame
};

/// The bearing of (x, y) (the scan's laser frame) past the scan's first beam, in [0, 2 pi).
double PastFirstBeam(const LaserScan& scan, double x, double y) {
  const double rel = std::atan2(y, x) - scan.angle_min_rad;
  return rel - kTwoPi * std::floor(rel / kTwoPi);
}

/// How much farther than a point a beam judged alone must pass it: half a beam's bearing
/// error, at `distance_m`, on a surface the beam meets at an angle of sine sin_a, moves the
/// beam's end along it by that much.
double BearingSlack(const LaserScan& scan, double distance_m, double sin_a) {
  const double cos_a = std::sqrt(std::max(0.0, 1.0 - sin_a * sin_a));
  return distance_m * 0.5 * std::abs(scan.angle_increment_rad) * cos_a / sin_a;
}

/// `alone`: the beam at the point's bearing judges it by itself, so the scan's first and last
/// beams may; otherwise the beams on both sides must exist too (three beams judge a point).
Seen SeenFrom(const LaserScan& scan, const Frame& T_laser_world, double wx, double wy, bool alone) {
  double x = 0.0, y = 0.0;
  T_laser_world.Apply(wx, wy, &x, &y);
  Seen s;
  s.x = x;
  s.y = y;
  s.distance_m = std::hypot(x, y);
  if (s.distance_m < 1e-3 || scan.angle_increment_rad <= 0.0) return s;
  const long k = std::lround(PastFirstBeam(scan, x, y) / scan.angle_increment_rad);
  const long edge = alone ? 0 : 1;
  if (k >= edge && k + edge < static_cast<long>(scan.ranges_m.size())) s.beam = k;
  return s;
}

enum class Verdict { kNone, kAgree, kHidden, kSeenThrough };

/// How `scan` sees a point: a return along its beam within margin of it (agree), its beam's
/// return short of it by more than `hidden` (hidden), or all three beams k-1, k, k+1 (only k
/// when `alone`) returns beyond d + margin and no return of the scan within guard of the
/// point (seen through). The last condition keeps the edge of an object, which a small error
/// of the poses moves off the object's outline, from reading as a change.
Verdict Judge(const LaserScan& scan, const Seen& p, double margin, double guard, double hidden,
              bool alone) {
  const auto i = static_cast<std::size_t>(p.beam);
  const double d = p.distance_m;
  if (scan.IsReturn(i) && std::abs(scan.ranges_m[i] - d) <= margin) return Verdict::kAgree;
  if (scan.IsReturn(i) && scan.ranges_m[i] < d - hidden) return Verdict::kHidden;
  for (std::size_t j = alone ? i : i - 1; j <= (alone ? i : i + 1); ++j) {
    if (!scan.IsReturn(j) || scan.ranges_m[j] <= d + margin) return Verdict::kNone;
  }
  // The beams whose returns could lie within guard of the point: those within
  // asin(guard / d) of its bearing (all of them when it is that close).
  const std::size_t n = scan.ranges_m.size();
  const double half = d > guard ? std::asin(guard / d) : kTwoPi;
  const auto w = static_cast<std::size_t>(std::ceil(half / scan.angle_increment_rad)) + 1;
  const std::size_t lo = i > w ? i - w : 0, hi = std::min(n - 1, i + w);
  for (std::size_t j = lo; j <= hi; ++j) {
    if (!scan.IsReturn(j)) continue;
    const double r = scan.ranges_m[j], b = scan.Bearing(j);
    if (std::hypot(r * std::cos(b) - p.x, r * std::sin(b) - p.y) <= guard) return Verdict::kNone;
  }
  return Verdict::kSeenThrough;
}

/// How far behind the other scan's return a return is hidden from it (hidden_m; a value under
/// margin_m acts as margin_m).
double HiddenM(const ChangeDetectionConfig& config) {
  return std::max(config.margin_m, config.hidden_m);
}

/// Judges every return of `from` as `to` sees it; f(from_beam, to_beam, distance from
/// to's laser) for those seen through. Counts agreement into *c. With `unseen`, the returns
/// of `from` that lie outside `to`'s field of view (ascending).
template <typename F>
void Judge(const LaserScan& from, const Pose2& T_world_from, const LaserScan& to,
           const Pose2& T_world_to, const ChangeDetectionConfig& config, double min_incidence_rad,
           bool alone, ScanComparison* c, F&& seen_through,
           std::vector<std::uint32_t>* unseen = nullptr) {
  const Frame T_to_world(T_world_to.Inverse());
  const Frame T_from(T_world_from);
  const std::size_t n = from.ranges_m.size();
  const std::vector<std::array<double, 2>> directions = Directions(from);
  const auto end_point = [&](std::size_t i) {
    const double r = from.ranges_m[i];
    Eigen::Vector2d p;
    T_from.Apply(r * directions[i][0], r * directions[i][1], &p.x(), &p.y());
    return p;
  };
  const double min_sin = std::sin(min_incidence_rad);
  const double hidden = HiddenM(config);
  for (std::size_t i = 0; i < n; ++i) {
    if (!from.IsReturn(i)) continue;
    const Eigen::Vector2d p = end_point(i);
    const Seen s = SeenFrom(to, T_to_world, p.x(), p.y(), alone);
    if (s.beam < 0) {
      if (unseen && s.distance_m >= 1e-3) unseen->push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    const Verdict v = Judge(to, s, config.margin_m, config.edge_guard_m, hidden, alone);
    ++c->judged;
    if (v == Verdict::kAgree) ++c->agree;
    if (v == Verdict::kHidden) ++c->hidden;
    if (v != Verdict::kSeenThrough) continue;
    // The surface at the point, from its neighbours: a beam of `to` that meets it at a
    // grazing angle passes it by a range error of (pose error) / sin(angle), no change. A
    // neighbour on a nearer surface that hides the rest (occlusion) leaves the point itself.
    if (i == 0 || i + 1 >= n) continue;
    const bool glimpses = config.min_run_occluded_beams > 0;
    const std::size_t lo = glimpses && change_runs::Occludes(from, i - 1, i, hidden) ? i : i - 1;
    const std::size_t hi = glimpses && change_runs::Occludes(from, i + 1, i, hidden) ? i : i + 1;
    if (lo == hi || !from.IsReturn(lo) || !from.IsReturn(hi)) continue;
    const Eigen::Vector2d t = end_point(hi) - end_point(lo);
    if (t.norm() > 4.0 * config.margin_m || t.norm() < 1e-9) continue;
    const Eigen::Vector2d origin(T_world_to.x, T_world_to.y);
    const Eigen::Vector2d u = (p - origin).normalized();
    const double sin_a = std::abs(u.x() * t.y() - u.y() * t.x()) / t.norm();
    if (sin_a < min_sin) continue;
    // A beam judged alone, without its neighbours, may be half a beam off the point's
    // bearing: on a surface met at angle a that moves its end by d (increment / 2) / tan(a)
    // along it, so it must pass the point by that much more.
    if (alone) {
      const double slack = BearingSlack(to, s.distance_m, sin_a);
      if (to.ranges_m[static_cast<std::size_t>(s.beam)] <= s.distance_m + config.margin_m + slack)
        continue;
    }
    ++c->disagree;
    seen_through(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(s.beam), s.distance_m);
  }
}

void SortUnique(std::vector<std::uint32_t>* v) {
  std::sort(v->begin(), v->end());
  v->erase(std::unique(v->begin(), v->end()), v->end());
}

/// By beam, each beam once, the cuts of a beam merged (Merge).
void SortUnique(std::vector<BeamCut>* v) {
  std::sort(v->begin(), v->end(),
            [](const BeamCut& a, const BeamCut& b) { return a.beam < b.beam; });
  std::size_t n = 0;
  for (std::size_t i = 0; i < v->size(); ++i) {
    if (n > 0 && (*v)[n - 1].beam == (*v)[i].beam) {
      (*v)[n - 1] = Merge((*v)[n - 1], (*v)[i]);
    } else {
      (*v)[n++] = (*v)[i];
    }
  }
  v->resize(n);
}

/// The older beam cut where it passed a surface now standing at distance_m along it: free up
/// to margin_m short of the surface, then traced again past the object's unseen depth behind
/// it to its return (kept: the room behind a door now closed was free when the beam crossed
/// it, and the wall it hit still stands).
BeamCut CutBefore(const LaserScan& older, std::uint32_t beam, double distance_m,
                  const ChangeDetectionConfig& config) {
  const double r = older.ranges_m[beam];
  const double resume =
      std::max(distance_m + config.margin_m,
               std::min(r - config.margin_m, distance_m + config.margin_m + config.added_depth_m));
  return {beam, static_cast<float>(std::max(0.0, distance_m - config.margin_m)),
          static_cast<float>(resume)};
}

/// Every older beam that crosses the newer surface between a return of an added run
/// (`added_news`, ascending) and its neighbouring returns: seen from afar such returns lie a
/// beam's width apart, wider than the older beams through the same doorway seen up close,
/// and the point test cuts only the older beam nearest each return. The neighbours of a
/// run's ends count too: a door's returns by its jambs are no evidence (edge_guard_m), yet
/// the door spans up to them. A beam must meet the surface at min_incidence_added_rad and
/// pass it as the point test asks (margin_m and half a beam's bearing error).
void CutAcrossSurfaces(const LaserScan& older, const Pose2& T_world_old_laser,
                       const LaserScan& newer, const Pose2& T_world_new_laser,
                       const std::vector<std::uint32_t>& added_news,
                       const ChangeDetectionConfig& config, std::vector<BeamCut>* out) {
  const Frame T_new(T_world_new_laser);
  const Frame T_old_world(T_world_old_laser.Inverse());
  const std::vector<std::array<double, 2>>& dir_new = Directions(newer);
  const auto in_old = [&](std::uint32_t j) {  // newer return j in the older laser's frame
    const double r = newer.ranges_m[j];
    double wx = 0.0, wy = 0.0;
    T_new.Apply(r * dir_new[j][0], r * dir_new[j][1], &wx, &wy);
    Eigen::Vector2d p;
    T_old_world.Apply(wx, wy, &p.x(), &p.y());
    return p;
  };
  const double inc = older.angle_increment_rad;
  const double min_sin = std::sin(config.min_incidence_added_rad);
  const auto n = static_cast<long>(older.ranges_m.size());
  std::vector<std::uint32_t> starts;  // j: the surface from newer return j to j + 1
  for (const std::uint32_t j : added_news) {
    if (j > 0) starts.push_back(j - 1);
    starts.push_back(j);
  }
  SortUnique(&starts);
  for (const std::uint32_t j : starts) {
    if (j + 1 >= newer.ranges_m.size() || !newer.IsReturn(j) || !newer.IsReturn(j + 1)) continue;
    const Eigen::Vector2d p = in_old(j), q = in_old(j + 1);
    const Eigen::Vector2d pq = q - p;
    if (pq.norm() > 4.0 * config.margin_m || pq.norm() < 1e-9 || inc <= 0.0) continue;
    // p's bearing past the first beam, negative when it lies just before it (the surface
    // may cross into the field of view there): within half a turn of the view's middle.
    double a0 = PastFirstBeam(older, p.x(), p.y());
    if (a0 > 0.5 * static_cast<double>(n - 1) * inc + 0.5 * kTwoPi) a0 -= kTwoPi;
    double span = std::atan2(q.y(), q.x()) - std::atan2(p.y(), p.x());
    span -= kTwoPi * std::round(span / kTwoPi);
    const double lo = std::min(a0, a0 + span), hi = std::max(a0, a0 + span);
    for (long i = std::max(0L, static_cast<long>(std::ceil(lo / inc)));
         i <= std::min(n - 1, static_cast<long>(std::floor(hi / inc))); ++i) {
      const auto b = static_cast<std::uint32_t>(i);
      if (!older.IsReturn(b)) continue;
      const Eigen::Vector2d u(std::cos(older.Bearing(b)), std::sin(older.Bearing(b)));
      const double cross = u.x() * pq.y() - u.y() * pq.x();  // u x pq
      const double sin_a = std::abs(cross) / pq.norm();
      if (sin_a < min_sin) continue;
      const double t = (p.x() * pq.y() - p.y() * pq.x()) / cross;  // o + t u on p + s pq
      if (t <= 0.0) continue;
      if (older.ranges_m[b] <= t + config.margin_m + BearingSlack(older, t, sin_a)) continue;
      out->push_back(CutBefore(older, b, t, config));
    }
  }
}

}  // namespace

ScanComparison CompareScans(const LaserScan& older, const Pose2& T_world_older,
                            const LaserScan& newer, const Pose2& T_world_newer,
                            const ChangeDetectionConfig& config) {
  const Pose2 T_world_old_laser = T_world_older * older.T_robot_laser;
  const Pose2 T_world_new_laser = T_world_newer * newer.T_robot_laser;
  const auto min_run = static_cast<std::size_t>(config.min_run_beams);
  ScanComparison c;
  // The older scan's returns that the newer one sees through: removed objects. The older
  // beams must lie in a run (a change covers neighbouring returns).
  std::vector<BeamCut> removed;
  std::vector<std::uint32_t> removed_news;
  Judge(older, T_world_old_laser, newer, T_world_new_laser, config, config.min_incidence_rad, false,
        &c, [&](std::uint32_t old_beam, std::uint32_t new_beam, double) {
          removed.push_back({old_beam, older.ranges_m[old_beam]});
          removed_news.push_back(new_beam);
        });
  // The newer scan's returns that the older one saw through: added objects. Here the newer
  // returns must lie in a run, and every older beam through one of them is outdated, its
  // neighbours or not: a beam that grazes a doorway from afar passes many of the door's
  // returns, alone among its neighbours.
  std::vector<std::pair<std::uint32_t, BeamCut>> added;  // (newer beam, older beam cut)
  std::vector<std::uint32_t> unseen;  // newer returns outside the older scan's view
  Judge(
      newer, T_world_new_laser, older, T_world_old_laser, config, config.min_incidence_added_rad,
      true, &c,
      [&](std::uint32_t new_beam, std::uint32_t old_beam, double distance_m) {
        added.push_back({new_beam, CutBefore(older, old_beam, distance_m, config)});
      },
      &unseen);
  // A point hidden behind a nearer return of the other scan says nothing of the poses: the
  // other scan saw something else there (a wall from another room, an object since moved).
  c.compared = Agrees(c, config.min_agreement);
  if (!c.compared) return c;
  SortUnique(&removed);
  KeepRuns(min_run, &removed);
  SortUnique(&removed_news);
  KeepRuns(min_run, &removed_news);
  std::vector<std::uint32_t> added_news;
  for (const auto& a : added) added_news.push_back(a.first);
  SortUnique(&added_news);
  KeepRunsToTheEdge(min_run, newer, unseen, 4.0 * config.margin_m,
                    {static_cast<std::size_t>(config.min_run_occluded_beams), HiddenM(config)},
                    &added_news);
  c.outdated = removed;
  for (const auto& [new_beam, cut] : added) {
    if (std::binary_search(added_news.begin(), added_news.end(), new_beam))
      c.outdated.push_back(cut);
  }
  CutAcrossSurfaces(older, T_world_old_laser, newer, T_world_new_laser, added_news, config,
                    &c.outdated);
  SortUnique(&c.outdated);
  c.news = removed_news;
  c.news.insert(c.news.end(), added_news.begin(), added_news.end());
  SortUnique(&c.news);
  return c;
}

bool Agrees(const ScanComparison& c, double min_agreement) {
  const int visible = c.judged - c.hidden;
  return visible > 0 && c.agree >= min_agreement * visible;
}

}  // namespace lifelong::slam
