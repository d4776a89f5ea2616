// Tracing a scan into the counting grid: the per-cell increments of its beams
// (GridMap::TouchedCells).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "slam/grid/grid_map.hpp"
#include "slam/grid/scratch_table.hpp"

namespace lifelong::slam {

namespace {

// Calls f(x, y) for every cell on the Bresenham line from a to b, both inclusive.
template <typename F>
void Bresenham(CellIndex a, CellIndex b, F&& f) {
  const int dx = std::abs(b.x - a.x), dy = -std::abs(b.y - a.y);
  const int sx = a.x < b.x ? 1 : -1, sy = a.y < b.y ? 1 : -1;
  int err = dx + dy, x = a.x, y = a.y;
  while (true) {
    f(x, y);
    if (x == b.x && y == b.y) return;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y += sy;
    }
  }
}

struct Beam {
  CellIndex start, end;  ///< traced from start (the laser's cell, or where a cut beam resumes)
  bool hit;
};

// Accumulate for a large bounding box: every traversed cell listed, sorted by (y, x) and
// summed.
std::vector<CellUpdate> AccumulateSorted(const std::vector<Beam>& beams) {
  std::vector<CellUpdate> out;
  for (const Beam& b : beams) {
    Bresenham(b.start, b.end, [&](int x, int y) {
      const bool hit = b.hit && x == b.end.x && y == b.end.y;
      out.push_back({{x, y}, {hit ? 1u : 0u, hit ? 0u : 1u}});
    });
  }
  std::sort(out.begin(), out.end(), [](const CellUpdate& a, const CellUpdate& b) {
    return a.cell.y != b.cell.y ? a.cell.y < b.cell.y : a.cell.x < b.cell.x;
  });
  std::size_t n = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (n > 0 && out[n - 1].cell == out[i].cell) {
      out[n - 1].delta.hits += out[i].delta.hits;
      out[n - 1].delta.misses += out[i].delta.misses;
    } else {
      out[n++] = out[i];
    }
  }
  out.resize(n);
  return out;
}
// Sums the beams' increments per cell, each cell once, ordered by (y, x). When the scan's
// bounding box is small, counts go into a dense scratch box kept per thread (a fresh one
// costs more in page faults and zeroing than the scan itself); each row is read back over
// the span of columns its beams touched, and zeroed for the next call. A sort otherwise.
std::vector<CellUpdate> Accumulate(const std::vector<Beam>& beams, CellIndex lo, CellIndex hi) {
  constexpr std::int64_t kMaxDenseCells = std::int64_t{1} << 21;
  const std::int64_t w = hi.x - lo.x + 1, h = hi.y - lo.y + 1;
  std::vector<CellUpdate> out;
  if (w * h <= kMaxDenseCells) {
    thread_local std::vector<CellCounts> box;  // all zero between calls
    thread_local std::vector<int> row_first, row_last;
    if (box.size() < static_cast<std::size_t>(w * h)) {
      ResizeTable(&box, static_cast<std::size_t>(w * h));  // still all zero
    }
    row_first.assign(static_cast<std::size_t>(h), static_cast<int>(w));
    row_last.assign(static_cast<std::size_t>(h), -1);
    std::size_t distinct = 0;
    for (const Beam& b : beams) {
      Bresenham(b.start, b.end, [&](int x, int y) {
        const int bx = x - lo.x;
        const auto by = static_cast<std::size_t>(y - lo.y);
        CellCounts& c = box[by * static_cast<std::size_t>(w) + static_cast<std::size_t>(bx)];
        if (c.hits == 0 && c.misses == 0) ++distinct;
        ++(b.hit && x == b.end.x && y == b.end.y ? c.hits : c.misses);
        row_first[by] = std::min(row_first[by], bx);
        row_last[by] = std::max(row_last[by], bx);
      });
    }
    const auto drain = [&](bool keep) {
      for (std::size_t by = 0; by < static_cast<std::size_t>(h); ++by) {
        CellCounts* row = box.data() + by * static_cast<std::size_t>(w);
        for (int bx = row_first[by]; bx <= row_last[by]; ++bx) {
          CellCounts& c = row[bx];
          if (c.hits == 0 && c.misses == 0) continue;
          if (keep) out.push_back({{lo.x + bx, lo.y + static_cast<int>(by)}, c});
          c = CellCounts{};
        }
      }
    };
    try {
      out.reserve(distinct);  // the only step that can throw: the box must end all zero
    } catch (...) {
      drain(false);
      throw;
    }
    drain(true);
    return out;
  }
  return AccumulateSorted(beams);
}

}  // namespace

namespace {

// Per beam, how far a "no return" beam may clear: for a dropout (a run of at most
// max_dropout_beams of them between two returns, or between the scan's end and a return),
// one cell short of the nearer return; otherwise unbounded. Written into *out (reused, so the
// hot path allocates nothing once it has seen its widest scan).
void DropoutClearRanges(const LaserScan& scan, const GridMapConfig& config,
                        std::vector<double>* out) {
  const std::size_t n = scan.ranges_m.size();
  out->assign(n, std::numeric_limits<double>::infinity());
  if (config.max_dropout_beams <= 0) return;
  const auto run_max = static_cast<std::size_t>(config.max_dropout_beams);
  for (std::size_t i = 0; i < n;) {
    if (scan.IsReturn(i)) {
      ++i;
      continue;
    }
    std::size_t end = i;  // [i, end) is a run of "no return" beams
    while (end < n && !scan.IsReturn(end)) ++end;
    // At the first or last beam of the scan the one return beside the run stands for both.
    if ((i > 0 || end < n) && end - i <= run_max) {
      const double before = i > 0 ? scan.ranges_m[i - 1] : scan.ranges_m[end];
      const double after = end < n ? scan.ranges_m[end] : scan.ranges_m[i - 1];
      const double nearer = std::min(before, after);
      std::fill(out->begin() + static_cast<std::ptrdiff_t>(i),
                out->begin() + static_cast<std::ptrdiff_t>(end), nearer - config.resolution_m);
    }
    i = end;
  }
}

// Whether beam i's return is a hit of the map: returns beyond the usable range are too sparse
// and too noisy to map (one beam per cell at best), and like "no return" beams only clear space.
bool TakesHit(const LaserScan& scan, std::size_t i, const GridMapConfig& config) {
  return scan.IsReturn(i) && scan.ranges_m[i] <= config.max_hit_range_m;
}

// The cell at distance d along the beam with this bearing from the laser at T_world_laser.
CellIndex AlongBeam(const GridMap& map, const Pose2& T_world_laser, double bearing, double d) {
  double x = 0.0, y = 0.0;
  T_world_laser.Apply(d * std::cos(bearing), d * std::sin(bearing), &x, &y);
  return map.CellOf(x, y);
}

}  // namespace

std::vector<CellIndex> GridMap::ReturnCells(const LaserScan& scan,
                                            const Pose2& T_world_robot) const {
  const Pose2 T_world_laser = T_world_robot * scan.T_robot_laser;
  std::vector<CellIndex> cells;
  cells.reserve(scan.ranges_m.size());
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (TakesHit(scan, i, config_)) {
      cells.push_back(AlongBeam(*this, T_world_laser, scan.Bearing(i), scan.ranges_m[i]));
    }
  }
  return cells;
}

std::vector<CellUpdate> GridMap::TouchedCells(const LaserScan& scan, const Pose2& T_world_robot,
                                              const std::vector<BeamCut>& cuts) const {
  const Pose2 T_world_laser = T_world_robot * scan.T_robot_laser;
  const CellIndex origin = CellOf(T_world_laser.x, T_world_laser.y);
  thread_local std::vector<double> dropout_clear;
  DropoutClearRanges(scan, config_, &dropout_clear);
  std::vector<Beam> beams;
  beams.reserve(scan.ranges_m.size());
  CellIndex lo = origin, hi = origin;
  auto cut = cuts.begin();
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    while (cut != cuts.end() && cut->beam < i) ++cut;
    const bool is_cut = cut != cuts.end() && cut->beam == i;
    const double r = scan.ranges_m[i];
    if (!(r > 0.0)) continue;
    const bool hit = TakesHit(scan, i, config_);  // else it clears up to max_free_range_m
    const double range = hit ? r : std::min({r, config_.max_free_range_m, dropout_clear[i]});
    const double a = scan.Bearing(i);
    const auto at = [&](double d) { return AlongBeam(*this, T_world_laser, a, d); };
    const auto add = [&](CellIndex start, double to, bool with_hit) {
      const CellIndex end = at(to);
      beams.push_back({start, end, with_hit});
      lo = {std::min(lo.x, end.x), std::min(lo.y, end.y)};
      hi = {std::max(hi.x, end.x), std::max(hi.y, end.y)};
    };
    if (!is_cut) {
      if (range > 0.0) add(origin, range, hit);
      continue;
    }
    // A cut beam shows free space only, as far as a beam without a return would.
    const double free_to = std::min(
        {r, config_.max_free_range_m, dropout_clear[i], static_cast<double>(cut->free_to_m)});
    if (free_to > 0.0) add(origin, free_to, false);
    if (cut->Resumes() && cut->resume_m < range) add(at(cut->resume_m), range, hit);
  }
  std::vector<CellUpdate> out = Accumulate(beams, lo, hi);
  if (config_.hits_mask_own_misses) {  // a cell the scan hit keeps none of its misses
    for (CellUpdate& u : out) {
      if (u.delta.hits > 0) u.delta.misses = 0;
    }
  }
  return out;
}

}  // namespace lifelong::slam
