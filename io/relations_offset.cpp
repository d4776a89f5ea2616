// Relations clock detection; see relations_offset.hpp.
#include "io/relations_offset.hpp"

#include <algorithm>
#include <cmath>

namespace lifelong::io {
namespace {

bool OnScan(const std::vector<double>& sorted, double t, double tol) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), t - tol);
  return it != sorted.end() && *it <= t + tol;
}

/// Up to n elements of v, evenly spread (all of v when it is shorter).
template <typename T>
std::vector<T> Spread(const std::vector<T>& v, std::size_t n) {
  if (v.size() <= n) return v;
  std::vector<T> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back(v[i * (v.size() - 1) / (n - 1)]);
  return out;
}

/// The scan stamp nearest t.
double Nearest(const std::vector<double>& sorted, double t) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), t);
  if (it == sorted.end()) return sorted.back();
  if (it == sorted.begin()) return *it;
  return (t - *std::prev(it) < *it - t) ? *std::prev(it) : *it;
}

/// Centres the offset on the matched stamps: the candidate came from one anchor's nearest
/// scan, which can sit up to the tolerance away from the clock's true offset; then the
/// nearest scan of a stamp can change where two scans are close in time.
double Refine(const std::vector<Relation>& relations, const std::vector<double>& sorted,
              double offset_s, double tol) {
  std::vector<double> residual;
  for (const Relation& r : relations) {
    if (!OnScan(sorted, r.t1_s - offset_s, tol) || !OnScan(sorted, r.t2_s - offset_s, tol)) {
      continue;
    }
    for (double t : {r.t1_s - offset_s, r.t2_s - offset_s})
      residual.push_back(t - Nearest(sorted, t));
  }
  if (residual.empty()) return offset_s;
  auto mid = residual.begin() + static_cast<std::ptrdiff_t>(residual.size() / 2);
  std::nth_element(residual.begin(), mid, residual.end());
  return offset_s + *mid;
}

}  // namespace

std::size_t CountMatchedRelations(const std::vector<Relation>& relations,
                                  const std::vector<double>& sorted_scan_stamps, double offset_s,
                                  double tolerance_s) {
  std::size_t n = 0;
  for (const Relation& r : relations) {
    n += OnScan(sorted_scan_stamps, r.t1_s - offset_s, tolerance_s) &&
                 OnScan(sorted_scan_stamps, r.t2_s - offset_s, tolerance_s)
             ? 1
             : 0;
  }
  return n;
}

OffsetDetection DetectRelationsOffset(const std::vector<Relation>& relations,
                                      const std::vector<double>& sorted_scan_stamps,
                                      double tolerance_s) {
  OffsetDetection best;
  if (relations.empty() || sorted_scan_stamps.empty()) return best;
  std::vector<double> candidates{0.0};
  for (const Relation& anchor : Spread(relations, 8)) {
    for (double s : sorted_scan_stamps) candidates.push_back(anchor.t1_s - s);
  }
  // Stage 1 scores every candidate on a few relations; stage 2 counts the leaders in full.
  const std::vector<Relation> sample = Spread(relations, 16);
  std::vector<std::size_t> score(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    score[i] = CountMatchedRelations(sample, sorted_scan_stamps, candidates[i], tolerance_s);
  }
  const std::size_t lead = *std::max_element(score.begin(), score.end());
  if (lead == 0) return best;
  std::vector<double> leaders;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (score[i] == lead) leaders.push_back(candidates[i]);
  }
  // Regular stamps can tie many candidates; the 64 smallest offsets are counted.
  std::sort(leaders.begin(), leaders.end(),
            [](double a, double b) { return std::abs(a) < std::abs(b); });
  leaders.resize(std::min<std::size_t>(leaders.size(), 64));
  for (double c : leaders) {
    const std::size_t n = CountMatchedRelations(relations, sorted_scan_stamps, c, tolerance_s);
    if (n > best.matched) {
      best = {c, n, std::nullopt};
    } else if (n == best.matched && !best.also_fits_s &&
               std::abs(c - best.offset_s) > tolerance_s && best.offset_s != 0.0) {
      best.also_fits_s = c;
    }
  }
  if (best.offset_s != 0.0) {
    const double refined = Refine(relations, sorted_scan_stamps, best.offset_s, tolerance_s);
    const std::size_t n =
        CountMatchedRelations(relations, sorted_scan_stamps, refined, tolerance_s);
    if (n >= best.matched) {
      best.offset_s = refined;
      best.matched = n;
    }
  }
  return best;
}

std::size_t CountRelationsInside(const std::vector<Relation>& relations, double first_s,
                                 double last_s, double offset_s) {
  std::size_t n = 0;
  for (const Relation& r : relations) {
    const double a = r.t1_s - offset_s, b = r.t2_s - offset_s;
    if (a >= first_s && a <= last_s && b >= first_s && b <= last_s) ++n;
  }
  return n;
}

std::vector<Relation> ShiftRelations(std::vector<Relation> relations, double offset_s) {
  for (Relation& r : relations) {
    r.t1_s -= offset_s;
    r.t2_s -= offset_s;
  }
  return relations;
}

}  // namespace lifelong::io
