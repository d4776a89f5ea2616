// Correlative multi-resolution scan matching, Olson 2009; see scan_matcher.hpp.
#include "slam/matching/scan_matcher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>

#include <Eigen/Dense>

#include "slam/matching/scan_refiner.hpp"

namespace lifelong::slam {

namespace {

// The search lattice: rotations k in [-K, K], translations (i, j) in [-W, W]^2 fine cells.
struct Lattice {
  int K = 0, W = 0, top_level = 0;
  double step_rad = 0.0, res_m = 0.0;
};

// A block of 2^level x 2^level translations starting at (i, j), at rotation k.
struct Node {
  int k, i, j;
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

// Branch and bound over the lattice. Search() finds the best pose accepted by a predicate;
// every fine pose is scored at most once and kept for the covariance.
class Searcher {
 public:
  Searcher(const ReferenceGrid& ref, std::vector<std::vector<Eigen::Vector2i>> cells,
           const Lattice& l)
      : ref_(ref), cells_(std::move(cells)), l_(l) {
    for (const auto& rotated : cells_) {
      Box box{std::numeric_limits<int>::max(), std::numeric_limits<int>::max(),
              std::numeric_limits<int>::min(), std::numeric_limits<int>::min()};
      for (const Eigen::Vector2i& c : rotated) {
        box.x0 = std::min(box.x0, c.x()), box.y0 = std::min(box.y0, c.y());
        box.x1 = std::max(box.x1, c.x()), box.y1 = std::max(box.y1, c.y());
      }
      boxes_.push_back(box);
    }
  }

  /// accept(e): a fine pose may win; reach(n, level): the block may hold such a pose.
  template <typename Accept, typename Reach>
  Eval Search(Accept accept, Reach reach, Eval best) {
    // The blocks in descending order of bound: once one is no better than the best, none
    // after it is. Skipping the unreachable ones visits the others in the order a stable
    // sort of the reachable ones alone would give.
    for (const Node& n : TopLevel()) {
      if (n.bound <= best.score) break;
      if (reach(n, l_.top_level)) Descend(n, l_.top_level, accept, reach, &best);
    }
    return best;
  }
  const Eval& Evaluate(int k, int i, int j);
  const std::vector<Eval>& evals() const { return evals_; }
  /// Forgets the poses scored (not the top-level bounds): a search after this scores them in
  /// its own order.
  void ForgetEvaluations() {
    index_.clear();
    evals_.clear();
  }
  int bound_evaluations() const { return bound_evaluations_; }

 private:
  /// Every top-level block with its bound, stable-sorted by bound, descending: computed by
  /// the first search and read again by the next (the rival's), whose bounds are the same.
  /// The lattice holds at least one block, so an empty list is one not yet computed.
  const std::vector<Node>& TopLevel() {
    if (top_.empty()) {
      const int side = 1 << l_.top_level;
      for (int k = -l_.K; k <= l_.K; ++k) {
        for (int i = -l_.W; i <= l_.W; i += side) {
          for (int j = -l_.W; j <= l_.W; j += side) top_.push_back(MakeNode(k, i, j, l_.top_level));
        }
      }
      SortByBound(&top_);
    }
    return top_;
  }
  Node MakeNode(int k, int i, int j, int level) {
    ++bound_evaluations_;
    float sum = 0.0f;
    const Box& box = boxes_[static_cast<std::size_t>(k + l_.K)];
    if (!Cells(k).empty() && ref_.Contains(box.x0 + i, box.y0 + j) &&
        ref_.Contains(box.x1 + i, box.y1 + j)) {
      // Every point lands in the table: no bounds check per point (the same sum, in the
      // same order, as below).
      const float* table = ref_.BoundTable(level);
      const auto width = static_cast<std::ptrdiff_t>(ref_.width());
      for (const Eigen::Vector2i& c : Cells(k)) {
        sum += table[static_cast<std::ptrdiff_t>(c.y() + j) * width + (c.x() + i)];
      }
    } else {
      for (const Eigen::Vector2i& c : Cells(k)) sum += ref_.Bound(level, c.x() + i, c.y() + j);
    }
    return {k, i, j, sum / static_cast<float>(Cells(k).size())};
  }
  static void SortByBound(std::vector<Node>* nodes) {
    std::stable_sort(nodes->begin(), nodes->end(),
                     [](const Node& a, const Node& b) { return a.bound > b.bound; });
  }
  template <typename Accept, typename Reach>
  void Descend(const Node& n, int level, Accept& accept, Reach& reach, Eval* best) {
    if (level == 0) {
      const Eval& e = Evaluate(n.k, n.i, n.j);
      if (e.score > best->score && accept(e)) *best = e;
      return;
    }
    const int half = 1 << (level - 1);
    // At most four children, on the stack, in the order a stable sort by bound would give
    // (insertion sort: a child goes after those with a bound at least its own).
    std::array<Node, 4> children;
    std::size_t count = 0;
    for (int di : {0, half}) {
      for (int dj : {0, half}) {
        if (n.i + di <= l_.W && n.j + dj <= l_.W &&
            reach(Node{n.k, n.i + di, n.j + dj, 0.0f}, level - 1)) {
          const Node child = MakeNode(n.k, n.i + di, n.j + dj, level - 1);
          std::size_t at = count++;
          for (; at > 0 && children[at - 1].bound < child.bound; --at) {
            children[at] = children[at - 1];
          }
          children[at] = child;
        }
      }
    }
    for (std::size_t c = 0; c < count; ++c) {
      if (children[c].bound > best->score) Descend(children[c], level - 1, accept, reach, best);
    }
  }
  const std::vector<Eigen::Vector2i>& Cells(int k) const {
    return cells_[static_cast<std::size_t>(k + l_.K)];
  }

  // The cells' bounding box at one rotation.
  struct Box {
    int x0, y0, x1, y1;
  };
  const ReferenceGrid& ref_;
  std::vector<std::vector<Eigen::Vector2i>> cells_;
  std::vector<Box> boxes_;  // of cells_, by rotation
  Lattice l_;
  std::unordered_map<std::int64_t, std::size_t> index_;  // (k, i, j) -> evals_
  std::vector<Eval> evals_;
  std::vector<Node> top_;  // TopLevel()'s blocks
  int bound_evaluations_ = 0;
};

const Eval& Searcher::Evaluate(int k, int i, int j) {
  const std::int64_t key =
      (static_cast<std::int64_t>(k) * 65536 + (i + 32768)) * 65536 + (j + 32768);
  const auto found = index_.find(key);
  if (found != index_.end()) return evals_[found->second];
  double sum = 0.0, log_sum = 0.0;
  for (const Eigen::Vector2i& c : Cells(k)) {
    sum += ref_.Likelihood(c.x() + i, c.y() + j);
    log_sum += ref_.LogLikelihood(c.x() + i, c.y() + j);
  }
  index_.emplace(key, evals_.size());
  evals_.push_back({k, i, j, sum / static_cast<double>(Cells(k).size()), log_sum});
  return evals_.back();
}

Eigen::Vector3d Offset(const Eval& e, const Lattice& l) {
  return {e.i * l.res_m, e.j * l.res_m, e.k * l.step_rad};
}

bool Distinct(const Eval& e, const Eval& best, const Lattice& l, const MatcherConfig& c) {
  const Eigen::Vector3d d = Offset(e, l) - Offset(best, l);
  return d.head<2>().norm() >= c.ambiguity_radius_m || std::abs(d.z()) >= c.ambiguity_angle_rad;
}

// Whether a block of 2^level x 2^level translations holds a pose distinct from the best:
// a distinct heading, or a corner at least ambiguity_radius_m away.
bool MayBeDistinct(const Node& n, int level, const Eval& best, const Lattice& l,
                   const MatcherConfig& c) {
  if (std::abs(n.k - best.k) * l.step_rad >= c.ambiguity_angle_rad) return true;
  const int last = (1 << level) - 1;
  const double dx = std::max(std::abs(n.i - best.i), std::abs(n.i + last - best.i)) * l.res_m;
  const double dy = std::max(std::abs(n.j - best.j), std::abs(n.j + last - best.j)) * l.res_m;
  return std::hypot(dx, dy) >= c.ambiguity_radius_m;
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

// Scores the 3 x 3 x 3 neighbourhood of the best pose (for the covariance).
void EvaluateNeighbourhood(const Eval& best, const Lattice& l, Searcher* s) {
  for (int k = std::max(best.k - 1, -l.K); k <= std::min(best.k + 1, l.K); ++k) {
    for (int i = std::max(best.i - 1, -l.W); i <= std::min(best.i + 1, l.W); ++i) {
      for (int j = std::max(best.j - 1, -l.W); j <= std::min(best.j + 1, l.W); ++j) {
        s->Evaluate(k, i, j);
      }
    }
  }
}

}  // namespace

double ScoreAt(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points_in_cur,
               const Pose2& T_ref_cur) {
  if (points_in_cur.empty()) return 0.0;
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points_in_cur) {
    double x = 0.0, y = 0.0;
    T_ref_cur.Apply(p.x(), p.y(), &x, &y);
    const Eigen::Vector2i c = ref.CellOf({x, y});
    sum += ref.Likelihood(c.x(), c.y());
  }
  return sum / static_cast<double>(points_in_cur.size());
}

void CropToSearch(const std::vector<Eigen::Vector2d>& points_in_cur, const Pose2& T_ref_cur_guess,
                  const MatcherConfig& config, std::vector<Eigen::Vector2d>* reference) {
  if (points_in_cur.empty()) {
    reference->clear();
    return;
  }
  // The lattice as Match sets it up: rotations up to K steps, translations of -W .. W fine
  // cells, and blocks of up to coarse_factor cells starting at W (their bounds read past W).
  const double res = config.resolution_m;
  const double step = AngularStep(points_in_cur, config);
  const double max_turn = std::ceil(config.angular_window_rad / step) * step;
  const double W = std::ceil(config.linear_window_m / res);
  int side = 1;
  while (side < config.coarse_factor) side *= 2;
  // Each point sweeps an arc of half-angle max_turn about the guess. Along any axis, the arc
  // passes its extreme within max_turn of one of its ends, so the box of the two ends grown
  // by r (1 - cos max_turn) holds it; past a half turn the arc is the whole circle (2 r).
  constexpr double kPi = 3.14159265358979323846;
  const double sweep = max_turn < kPi ? 1.0 - std::cos(max_turn) : 2.0;
  const Eigen::Rotation2Dd R_lo(T_ref_cur_guess.theta - max_turn),
      R_hi(T_ref_cur_guess.theta + max_turn);
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (const Eigen::Vector2d& p : points_in_cur) {
    const Eigen::Vector2d a = R_lo * p, b = R_hi * p;
    const double grow = p.norm() * sweep;
    lo = lo.cwiseMin(a.cwiseMin(b) - Eigen::Vector2d::Constant(grow));
    hi = hi.cwiseMax(a.cwiseMax(b) + Eigen::Vector2d::Constant(grow));
  }
  // Translations, cell rounding on both ends, and the kernel (3 sigma) of the field.
  const Eigen::Vector2d guess(T_ref_cur_guess.x, T_ref_cur_guess.y);
  const double kernel = 3.0 * config.sigma_m;
  lo += guess - Eigen::Vector2d::Constant((W + 2.0) * res + kernel);
  hi += guess + Eigen::Vector2d::Constant((W + side + 2.0) * res + kernel);
  reference->erase(std::remove_if(reference->begin(), reference->end(),
                                  [&](const Eigen::Vector2d& p) {
                                    return (p.array() < lo.array()).any() ||
                                           (p.array() > hi.array()).any();
                                  }),
                   reference->end());
}

MatcherFootprint EstimateFootprint(const MatcherConfig& c, double linear_window_m,
                                   double angular_window_rad) {
  int side = 1, levels = 1;
  while (side < c.coarse_factor) side *= 2, ++levels;
  const double W = std::ceil(linear_window_m / c.resolution_m);
  // CropToSearch's box around a point-free scan: translations, blocks, kernel, rounding.
  const double cells = 2.0 * W + side + 2.0 * std::ceil(3.0 * c.sigma_m / c.resolution_m) + 4.0;
  MatcherFootprint f;
  f.table_bytes = cells * cells * (levels + 2) * 4.0;
  const double step = c.angular_step_rad > 0.0 ? c.angular_step_rad : c.resolution_m / 10.0;
  const double rotations = 2.0 * std::ceil(angular_window_rad / step) + 1.0;
  const double blocks = std::ceil((2.0 * W + 1.0) / side);
  f.frontier_bytes = rotations * blocks * blocks * static_cast<double>(sizeof(Node));
  return f;
}

MatchResult Match(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points_in_cur,
                  const Pose2& T_ref_cur_guess, const MatcherConfig& config) {
  MatchResult result;
  result.T_ref_cur = T_ref_cur_guess;
  if (points_in_cur.empty()) return result;
  Lattice l;
  l.res_m = ref.resolution_m();
  l.step_rad = AngularStep(points_in_cur, config);
  l.K = static_cast<int>(std::ceil(config.angular_window_rad / l.step_rad));
  l.W = static_cast<int>(std::ceil(config.linear_window_m / l.res_m));
  l.top_level = ref.num_levels() - 1;
  while (l.top_level > 0 && (1 << (l.top_level - 1)) > 2 * l.W) --l.top_level;
  std::vector<std::vector<Eigen::Vector2i>> cells =
      RotatedCells(ref, points_in_cur, T_ref_cur_guess, l);
  ref.PrepareBounds(cells, l.W, l.top_level);
  Searcher s(ref, std::move(cells), l);
  // When cutting, a first branch and bound starts a little below min_score: the bounds are
  // float sums, which may fall short of a pose's double score by their rounding (some 1e-5
  // over a few hundred points), and a pose at min_score must still be found. Where it finds
  // nothing, that is the answer. Where it finds a pose, the full search follows from a clean
  // slate, scoring the poses in its own order, so its result (the covariance's sums too) is
  // the full search's to the bit.
  constexpr double kBoundSlack = 1e-4;
  const auto anything = [](const Eval&) { return true; };
  const auto anywhere = [](const Node&, int) { return true; };
  if (config.cut_below_min_score &&
      !(s.Search(anything, anywhere, Eval{0, 0, 0, config.min_score - kBoundSlack, 0.0}).score >=
        config.min_score)) {
    result.score = result.ambiguity = std::numeric_limits<double>::quiet_NaN();
    result.evaluations = static_cast<int>(s.evals().size());
    result.bound_evaluations = s.bound_evaluations();
    return result;
  }
  s.ForgetEvaluations();
  // Branch and bound for the best pose, then for the best distinct competitor.
  const Eval best = s.Search(anything, anywhere, Eval{0, 0, 0, -1.0, 0.0});
  const Eval rival =
      s.Search([&](const Eval& e) { return Distinct(e, best, l, config); },
               [&](const Node& n, int level) { return MayBeDistinct(n, level, best, l, config); },
               Eval{0, 0, 0, 0.0, 0.0});
  EvaluateNeighbourhood(best, l, &s);
  result.T_ref_cur =
      Pose2(T_ref_cur_guess.x + best.i * l.res_m, T_ref_cur_guess.y + best.j * l.res_m,
            T_ref_cur_guess.theta + best.k * l.step_rad);
  if (config.refine) {
    result.T_ref_cur =
        RefinePose(ref, points_in_cur, result.T_ref_cur, l.res_m, l.step_rad).T_ref_cur;
  }
  result.score = best.score;
  result.ok = best.score >= config.min_score;
  result.ambiguity = best.score > 0.0 ? rival.score / best.score : 0.0;
  result.T_ref_rival =
      Pose2(T_ref_cur_guess.x + rival.i * l.res_m, T_ref_cur_guess.y + rival.j * l.res_m,
            T_ref_cur_guess.theta + rival.k * l.step_rad);
  result.covariance = Covariance(s.evals(), best, l, config);
  result.information = result.covariance.inverse();
  result.evaluations = static_cast<int>(s.evals().size());
  result.bound_evaluations = s.bound_evaluations();
  return result;
}

}  // namespace lifelong::slam
