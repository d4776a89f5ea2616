#include "eval/metrics/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lifelong::eval {
namespace {

constexpr double kRadToDeg = 57.29577951308232;

void RequireSameSize(std::size_t a, std::size_t b, const char* what) {
  if (a != b) throw std::invalid_argument(std::string(what) + ": estimate and truth sizes differ");
}

/// Mean and population standard deviation.
void MeanStd(const std::vector<double>& v, double* mean, double* std_dev) {
  double sum = 0.0;
  for (double x : v) sum += x;
  *mean = v.empty() ? 0.0 : sum / static_cast<double>(v.size());
  double sq = 0.0;
  for (double x : v) sq += (x - *mean) * (x - *mean);
  *std_dev = v.empty() ? 0.0 : std::sqrt(sq / static_cast<double>(v.size()));
}

/// Index of the pose whose stamp is nearest to t within tol in a stamp-sorted vector.
std::ptrdiff_t FindStamp(const std::vector<StampedPose>& sorted, double t, double tol) {
  auto it = std::lower_bound(sorted.begin(), sorted.end(), t,
                             [](const StampedPose& p, double s) { return p.stamp_s < s; });
  std::ptrdiff_t best = -1;
  double best_dt = tol;
  for (auto c : {it, it == sorted.begin() ? it : std::prev(it)}) {
    if (c == sorted.end()) continue;
    const double dt = std::abs(c->stamp_s - t);
    if (dt <= best_dt) {
      best_dt = dt;
      best = c - sorted.begin();
    }
  }
  return best;
}

std::vector<StampedPose> SortedByStamp(std::vector<StampedPose> v) {
  std::stable_sort(v.begin(), v.end(), [](const StampedPose& a, const StampedPose& b) {
    return a.stamp_s < b.stamp_s;
  });
  return v;
}

}  // namespace

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double pos = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  const double f = pos - static_cast<double>(lo);
  return values[lo] * (1.0 - f) + values[hi] * f;
}

Pose2 AlignSE2(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth) {
  RequireSameSize(estimate.size(), truth.size(), "AlignSE2");
  if (estimate.empty()) return Pose2();
  const double n = static_cast<double>(estimate.size());
  double ex = 0, ey = 0, tx = 0, ty = 0;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    ex += estimate[i].x, ey += estimate[i].y, tx += truth[i].x, ty += truth[i].y;
  }
  ex /= n, ey /= n, tx /= n, ty /= n;
  double dot = 0.0, cross = 0.0;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const double ax = estimate[i].x - ex, ay = estimate[i].y - ey;
    const double bx = truth[i].x - tx, by = truth[i].y - ty;
    dot += ax * bx + ay * by;
    cross += ax * by - ay * bx;
  }
  const double theta = (dot == 0.0 && cross == 0.0) ? 0.0 : std::atan2(cross, dot);
  const double c = std::cos(theta), s = std::sin(theta);
  return Pose2(tx - (c * ex - s * ey), ty - (s * ex + c * ey), theta);
}

AteResult ComputeAte(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth) {
  AteResult r;
  r.T_truth_est = AlignSE2(estimate, truth);
  r.count = estimate.size();
  if (r.count == 0) return r;
  double sq = 0.0, sum = 0.0, rot_sq = 0.0;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const Pose2 err = Between(truth[i], r.T_truth_est * estimate[i]);
    const double d = Norm(err);
    sq += d * d;
    sum += d;
    r.max_m = std::max(r.max_m, d);
    rot_sq += err.theta * err.theta;
  }
  const double n = static_cast<double>(r.count);
  r.rmse_m = std::sqrt(sq / n);
  r.mean_m = sum / n;
  r.rot_rmse_deg = std::sqrt(rot_sq / n) * kRadToDeg;
  return r;
}

MatchedPoses MatchByStamp(const std::vector<StampedPose>& estimate,
                          const std::vector<StampedPose>& truth, double tolerance_s) {
  const std::vector<StampedPose> sorted = SortedByStamp(truth);
  MatchedPoses m;
  for (const StampedPose& e : estimate) {
    const std::ptrdiff_t k = FindStamp(sorted, e.stamp_s, tolerance_s);
    if (k < 0) {
      ++m.unmatched;
      continue;
    }
    m.estimate.push_back(e.T_world_robot);
    m.truth.push_back(sorted[static_cast<std::size_t>(k)].T_world_robot);
  }
  return m;
}

RpeResult ComputeRpe(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth,
                     int delta) {
  RequireSameSize(estimate.size(), truth.size(), "ComputeRpe");
  if (delta < 1) throw std::invalid_argument("ComputeRpe: delta must be >= 1");
  RpeResult r;
  double t_sq = 0, t_sum = 0, r_sq = 0, r_sum = 0, path = 0;
  const std::size_t d = static_cast<std::size_t>(delta);
  for (std::size_t i = 0; i + d < truth.size(); ++i) {
    const Pose2 err =
        Between(Between(truth[i], truth[i + d]), Between(estimate[i], estimate[i + d]));
    const double t = Norm(err), a = std::abs(err.theta) * kRadToDeg;
    t_sq += t * t, t_sum += t, r_sq += a * a, r_sum += a;
    for (std::size_t k = i; k < i + d; ++k) path += Norm(Between(truth[k], truth[k + 1]));
    ++r.count;
  }
  if (r.count == 0) return r;
  const double n = static_cast<double>(r.count);
  r.trans_rmse_m = std::sqrt(t_sq / n);
  r.trans_mean_m = t_sum / n;
  r.rot_rmse_deg = std::sqrt(r_sq / n);
  r.rot_mean_deg = r_sum / n;
  if (path > 0.0) {
    r.trans_per_m = t_sum / path;
    r.rot_deg_per_m = r_sum / path;
  }
  return r;
}

RelationsResult ComputeRelationsError(const std::vector<StampedPose>& estimate,
                                      const std::vector<Relation>& relations, double tolerance_s) {
  const std::vector<StampedPose> sorted = SortedByStamp(estimate);
  std::vector<double> trans, rot;
  RelationsResult r;
  for (const Relation& rel : relations) {
    const std::ptrdiff_t a = FindStamp(sorted, rel.t1_s, tolerance_s);
    const std::ptrdiff_t b = FindStamp(sorted, rel.t2_s, tolerance_s);
    if (a < 0 || b < 0) {
      ++r.unmatched;
      continue;
    }
    const Pose2 est_rel = Between(sorted[static_cast<std::size_t>(a)].T_world_robot,
                                  sorted[static_cast<std::size_t>(b)].T_world_robot);
    const Pose2 err = Between(est_rel, rel.T_1_2);
    trans.push_back(Norm(err));
    rot.push_back(std::abs(err.theta) * kRadToDeg);
  }
  r.count = trans.size();
  MeanStd(trans, &r.trans_mean_m, &r.trans_std_m);
  MeanStd(rot, &r.rot_mean_deg, &r.rot_std_deg);
  return r;
}

namespace {

bool Within(const Pose2& a, const Pose2& b, double trans_m, double rot_deg) {
  const Pose2 d = Between(a, b);
  return Norm(d) <= trans_m && std::abs(d.theta) * kRadToDeg <= rot_deg;
}

/// Node n is a revisit when some node m <= n - gap lies within the revisit tolerances.
std::vector<bool> RevisitNodes(const std::vector<Pose2>& nodes, const LoopClosureConfig& c) {
  std::vector<bool> revisit(nodes.size(), false);
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    for (std::size_t m = 0; m + static_cast<std::size_t>(c.min_index_gap) <= n; ++m) {
      if (Within(nodes[m], nodes[n], c.revisit_dist_m, c.revisit_rot_deg)) {
        revisit[n] = true;
        break;
      }
    }
  }
  return revisit;
}

}  // namespace

LoopClosureResult ComputeLoopClosureStats(const std::vector<LoopClosure>& closures,
                                          const std::vector<Pose2>& true_nodes,
                                          const LoopClosureConfig& config) {
  LoopClosureResult r;
  const int n = static_cast<int>(true_nodes.size());
  std::vector<bool> recalled(true_nodes.size(), false);
  for (const LoopClosure& lc : closures) {
    if (lc.i < 0 || lc.j < 0 || lc.i >= n || lc.j >= n) {
      throw std::invalid_argument("ComputeLoopClosureStats: closure node index out of range");
    }
    ++r.accepted;
    const Pose2 true_rel = Between(true_nodes[static_cast<std::size_t>(lc.i)],
                                   true_nodes[static_cast<std::size_t>(lc.j)]);
    const bool correct = Within(true_rel, lc.T_i_j, config.correct_trans_m, config.correct_rot_deg);
    r.correct_each.push_back(correct);
    const Pose2 error = Between(true_rel, lc.T_i_j);
    r.error_m_each.push_back(Norm(error));
    r.error_deg_each.push_back(std::abs(error.theta) * kRadToDeg);
    if (!correct) continue;
    ++r.correct;
    const int newer = std::max(lc.i, lc.j), older = std::min(lc.i, lc.j);
    if (newer - older >= config.min_index_gap) recalled[static_cast<std::size_t>(newer)] = true;
  }
  const std::vector<bool> revisit = RevisitNodes(true_nodes, config);
  r.revisit_each = revisit;
  r.recalled_each.assign(revisit.size(), false);
  for (std::size_t k = 0; k < revisit.size(); ++k) r.recalled_each[k] = revisit[k] && recalled[k];
  for (std::size_t k = 0; k < revisit.size(); ++k) {
    if (!revisit[k]) continue;
    ++r.revisit_nodes;
    if (recalled[k]) ++r.recalled_nodes;
  }
  if (r.accepted > 0) r.precision = static_cast<double>(r.correct) / r.accepted;
  if (r.revisit_nodes > 0) r.recall = static_cast<double>(r.recalled_nodes) / r.revisit_nodes;
  return r;
}

std::vector<LoopCurvePoint> LoopCurve(const std::vector<TimelineRow>& timeline,
                                      const LoopClosureResult& truth) {
  const std::vector<bool>& correct_each = truth.correct_each;
  std::vector<LoopCurvePoint> curve;
  LoopCurvePoint p;
  int correct = 0, recalled = 0;
  for (std::size_t n = 0; n < timeline.size(); ++n) {
    p.t_s = timeline[n].t_s;
    p.obs = timeline[n].obs;
    const std::size_t accepted = std::min(
        static_cast<std::size_t>(std::max(timeline[n].loop_closures, 0)), correct_each.size());
    for (auto k = static_cast<std::size_t>(p.accepted); k < accepted; ++k) {
      ++p.accepted;
      correct += correct_each[k] ? 1 : 0;
    }
    if (n < truth.revisit_each.size() && truth.revisit_each[n]) {
      ++p.revisits;
      recalled += truth.recalled_each[n] ? 1 : 0;
    }
    p.precision = p.accepted > 0 ? static_cast<double>(correct) / p.accepted : 0.0;
    p.recall = p.revisits > 0 ? static_cast<double>(recalled) / p.revisits : 0.0;
    curve.push_back(p);
  }
  return curve;
}

bool StampsAdvance(const std::vector<LoopCurvePoint>& curve) {
  if (curve.size() < 2) return true;
  if (!(curve.back().t_s > curve.front().t_s)) return false;
  for (std::size_t i = 1; i < curve.size(); ++i) {
    if (curve[i].t_s < curve[i - 1].t_s) return false;
  }
  return true;
}

}  // namespace lifelong::eval
