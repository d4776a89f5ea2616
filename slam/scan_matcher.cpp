// Correlative multi-resolution scan matching, Olson 2009; see scan_matcher.hpp.
#include "slam/scan_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace lifelong::slam {

namespace {

// The search lattice: rotations k in [-K, K], translations (i, j) in [-W, W]^2 cells, cut in
// blocks of f x f translations; block (a, b) starts at (-W + a f, -W + b f).
struct Lattice {
  int K = 0, W = 0, f = 1, blocks = 0;  // blocks per axis
  double step_rad = 0.0, res_m = 0.0;
  int BlockStart(int a) const { return -W + a * f; }
  int BlockEnd(int a) const { return std::min(BlockStart(a) + f - 1, W); }
  int Id(int k, int a, int b) const { return ((k + K) * blocks + a) * blocks + b; }
};

struct Candidate {
  int k, a, b;
  float bound;
};

struct Eval {
  int k, i, j;
  double score, log_likelihood;
};

double AngularStep(const std::vector<Eigen::Vector2d>& points, const MatcherConfig& c) {
  if (c.angular_step_rad > 0.0) return c.angular_step_rad;
  double max_range = 0.0;
  for (const Eigen::Vector2d& p : points) max_range = std::max(max_range, p.norm());
  return c.resolution_m / std::clamp(max_range, 1.0, 10.0);
}

// Query points rotated by guess.theta + k step and translated by the guess, as table cells.
std::vector<std::vector<Eigen::Vector2i>> RotatedCells(const ReferenceGrid& ref,
                                                       const std::vector<Eigen::Vector2d>& pts,
                                                       const Pose2& guess, const Lattice& l) {
  std::vector<std::vector<Eigen::Vector2i>> out(static_cast<std::size_t>(2 * l.K + 1));
  for (int k = -l.K; k <= l.K; ++k) {
    const Eigen::Rotation2Dd R(guess.theta + k * l.step_rad);
    auto& cells = out[static_cast<std::size_t>(k + l.K)];
    cells.reserve(pts.size());
    for (const Eigen::Vector2d& p : pts) {
      cells.push_back(ref.CellOf(R * p + Eigen::Vector2d(guess.x, guess.y)));
    }
  }
  return out;
}

class Searcher {
 public:
  Searcher(const ReferenceGrid& ref, std::vector<std::vector<Eigen::Vector2i>> cells,
           const Lattice& l)
      : ref_(ref),
        cells_(std::move(cells)),
        l_(l),
        expanded_(static_cast<std::size_t>((2 * l.K + 1) * l.blocks * l.blocks), false) {}

  std::vector<Candidate> Candidates() const;
  void Expand(const Candidate& c) {
    expanded_[static_cast<std::size_t>(l_.Id(c.k, c.a, c.b))] = true;
    for (int i = l_.BlockStart(c.a); i <= l_.BlockEnd(c.a); ++i) {
      for (int j = l_.BlockStart(c.b); j <= l_.BlockEnd(c.b); ++j) Evaluate(c.k, i, j);
    }
  }
  const Eval& Evaluate(int k, int i, int j);
  bool IsEvaluated(int k, int i, int j) const {
    const int a = (i + l_.W) / l_.f, b = (j + l_.W) / l_.f;
    return expanded_[static_cast<std::size_t>(l_.Id(k, a, b))];
  }
  const std::vector<Eval>& evals() const { return evals_; }

 private:
  const ReferenceGrid& ref_;
  std::vector<std::vector<Eigen::Vector2i>> cells_;
  Lattice l_;
  std::vector<bool> expanded_;
  std::vector<Eval> evals_;
};

std::vector<Candidate> Searcher::Candidates() const {
  std::vector<Candidate> out;
  out.reserve(expanded_.size());
  for (int k = -l_.K; k <= l_.K; ++k) {
    const auto& cells = cells_[static_cast<std::size_t>(k + l_.K)];
    for (int a = 0; a < l_.blocks; ++a) {
      for (int b = 0; b < l_.blocks; ++b) {
        const int di = l_.BlockStart(a), dj = l_.BlockStart(b);
        float sum = 0.0f;
        for (const Eigen::Vector2i& c : cells) sum += ref_.CoarseBound(c.x() + di, c.y() + dj);
        out.push_back({k, a, b, sum / static_cast<float>(cells.size())});
      }
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Candidate& x, const Candidate& y) { return x.bound > y.bound; });
  return out;
}

const Eval& Searcher::Evaluate(int k, int i, int j) {
  const auto& cells = cells_[static_cast<std::size_t>(k + l_.K)];
  double sum = 0.0, log_sum = 0.0;
  for (const Eigen::Vector2i& c : cells) {
    sum += ref_.Likelihood(c.x() + i, c.y() + j);
    log_sum += ref_.LogLikelihood(c.x() + i, c.y() + j);
  }
  evals_.push_back({k, i, j, sum / static_cast<double>(cells.size()), log_sum});
  return evals_.back();
}

Eigen::Vector3d Offset(const Eval& e, const Lattice& l) {
  return {e.i * l.res_m, e.j * l.res_m, e.k * l.step_rad};
}

bool Distinct(const Eval& e, const Eval& best, const Lattice& l, const MatcherConfig& c) {
  const Eigen::Vector3d d = Offset(e, l) - Offset(best, l);
  return d.head<2>().norm() >= c.ambiguity_radius_m || std::abs(d.z()) >= c.ambiguity_angle_rad;
}

// Olson §III-C: probability-weighted second moments of the evaluated poses around the best.
Eigen::Matrix3d Covariance(const std::vector<Eval>& evals, const Eval& best, const Lattice& l,
                           const MatcherConfig& c) {
  double max_log = -std::numeric_limits<double>::infinity();
  for (const Eval& e : evals) max_log = std::max(max_log, e.log_likelihood);
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  double weight = 0.0;
  for (const Eval& e : evals) {
    const double w = std::exp(e.log_likelihood - max_log);
    const Eigen::Vector3d d = Offset(e, l) - Offset(best, l);
    m += w * d * d.transpose();
    weight += w;
  }
  m /= weight;
  const double q_t = l.res_m * l.res_m / 12.0, q_r = l.step_rad * l.step_rad / 12.0;
  m.diagonal() += Eigen::Vector3d(q_t + c.floor_sigma_m * c.floor_sigma_m,
                                  q_t + c.floor_sigma_m * c.floor_sigma_m,
                                  q_r + c.floor_sigma_rad * c.floor_sigma_rad);
  return m;
}

// Makes sure the 3 x 3 x 3 neighbourhood of the best pose is scored (for the covariance).
void EvaluateNeighbourhood(const Eval& best, const Lattice& l, Searcher* s) {
  for (int k = std::max(best.k - 1, -l.K); k <= std::min(best.k + 1, l.K); ++k) {
    for (int i = std::max(best.i - 1, -l.W); i <= std::min(best.i + 1, l.W); ++i) {
      for (int j = std::max(best.j - 1, -l.W); j <= std::min(best.j + 1, l.W); ++j) {
        if (!s->IsEvaluated(k, i, j)) s->Evaluate(k, i, j);
      }
    }
  }
}

}  // namespace

MatchResult Match(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points_in_cur,
                  const Pose2& T_ref_cur_guess, const MatcherConfig& config) {
  MatchResult result;
  result.T_ref_cur = T_ref_cur_guess;
  if (points_in_cur.empty()) return result;
  Lattice l;
  l.res_m = ref.resolution_m();
  l.f = ref.coarse_factor();
  l.step_rad = AngularStep(points_in_cur, config);
  l.K = static_cast<int>(std::ceil(config.angular_window_rad / l.step_rad));
  l.W = static_cast<int>(std::ceil(config.linear_window_m / l.res_m));
  l.blocks = (2 * l.W + l.f) / l.f;
  Searcher s(ref, RotatedCells(ref, points_in_cur, T_ref_cur_guess, l), l);
  const std::vector<Candidate> candidates = s.Candidates();
  // Branch and bound for the best pose, then for the best distinct competitor.
  std::size_t n = 0;
  Eval best{0, 0, 0, -1.0, 0.0};
  for (; n < candidates.size() && candidates[n].bound > best.score; ++n) {
    const std::size_t first = s.evals().size();
    s.Expand(candidates[n]);
    for (std::size_t e = first; e < s.evals().size(); ++e) {
      if (s.evals()[e].score > best.score) best = s.evals()[e];
    }
  }
  double rival = 0.0;
  for (const Eval& e : s.evals()) {
    if (Distinct(e, best, l, config)) rival = std::max(rival, e.score);
  }
  for (; n < candidates.size() && candidates[n].bound > rival; ++n) {
    const std::size_t first = s.evals().size();
    s.Expand(candidates[n]);
    for (std::size_t e = first; e < s.evals().size(); ++e) {
      if (Distinct(s.evals()[e], best, l, config)) rival = std::max(rival, s.evals()[e].score);
    }
  }
  EvaluateNeighbourhood(best, l, &s);
  result.T_ref_cur =
      Pose2(T_ref_cur_guess.x + best.i * l.res_m, T_ref_cur_guess.y + best.j * l.res_m,
            T_ref_cur_guess.theta + best.k * l.step_rad);
  result.score = best.score;
  result.ok = best.score >= config.min_score;
  result.ambiguity = best.score > 0.0 ? rival / best.score : 0.0;
  result.covariance = Covariance(s.evals(), best, l, config);
  result.information = result.covariance.inverse();
  result.evaluations = static_cast<int>(s.evals().size());
  result.coarse_evaluations = static_cast<int>(candidates.size());
  return result;
}

}  // namespace lifelong::slam
