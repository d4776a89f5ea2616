// Group verification of loop closures; see loop_verifier.hpp for the test and the rule.
#include "slam/loops/loop_verifier.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "slam/graph/se2.hpp"

namespace lifelong::slam {
namespace {

/// Covariance of a chain of incremental estimates d metres long, in its end frame: a
/// translational random walk plus the lateral error a heading random walk builds up
/// (integral of var_rad s ds over the chain: var_rad_per_m d^3 / 3).
Eigen::Matrix3d ChainCovariance(const LoopVerifierConfig& c, double d) {
  d = std::abs(d);
  const double xy = c.base_var_xy_m2 + c.var_xy_per_m * d + c.var_rad_per_m * d * d * d / 3.0;
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  S(0, 0) = S(1, 1) = xy;
  S(2, 2) = c.base_var_rad2 + c.var_rad_per_m * d;
  return S;
}

}  // namespace

bool LoopVerifier::Consistent(const LoopHypothesis& a, const LoopHypothesis& b,
                              const Values& values) const {
  const auto X = [&](NodeId id) -> const Pose2* {
    const auto it = values.find(id);
    return it == values.end() ? nullptr : &it->second;
  };
  const Pose2 *Xi = X(a.old), *Xj = X(a.current), *Xk = X(b.old), *Xl = X(b.current);
  if (!Xi || !Xj || !Xk || !Xl) return false;
  // C = Z_a * T_jl * Z_b^-1 * T_ki; right perturbations moved to the end of the product:
  // eps = Adj((F2 F3 F4)^-1) d1 + Adj((F3 F4)^-1) d2 + Adj(F4^-1) d3 + d4, and the
  // inverse's perturbation d3 = -Adj(Z_b) d_b.
  const Pose2 T_jl = Between(*Xj, *Xl);
  const Pose2 T_ki = Between(*Xk, *Xi);
  const Pose2 Zb_inv = b.T_old_current.Inverse();
  const Pose2 cycle = a.T_old_current * T_jl * Zb_inv * T_ki;
  Eigen::Vector3d e = T2V(cycle);
  e.z() = NormalizeAngle(e.z());
  const Eigen::Matrix3d A1 = Adjoint((T_jl * Zb_inv * T_ki).Inverse());
  const Eigen::Matrix3d A2 = Adjoint((Zb_inv * T_ki).Inverse());
  const Eigen::Matrix3d A3 = Adjoint(T_ki.Inverse()) * Adjoint(b.T_old_current);
  const double d_jl = std::abs(a.travelled_m - b.travelled_m);  // path between j and l
  const Eigen::Matrix3d S =
      A1 * a.covariance * A1.transpose() + A2 * ChainCovariance(config_, d_jl) * A2.transpose() +
      A3 * b.covariance * A3.transpose() + ChainCovariance(config_, std::hypot(T_ki.x, T_ki.y));
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(S);
  if (ldlt.info() != Eigen::Success) return false;
  return e.dot(ldlt.solve(e)) <= config_.consistency_chi2;
}

void LoopVerifier::Expire(double travelled_m) {
  const auto old = [&](const LoopHypothesis& h) {
    return h.travelled_m < travelled_m - config_.expiry_m;
  };
  stats_.expired += static_cast<int>(std::count_if(pending_.begin(), pending_.end(), old));
  pending_.erase(std::remove_if(pending_.begin(), pending_.end(), old), pending_.end());
  accepted_.erase(std::remove_if(accepted_.begin(), accepted_.end(),
                                 [&](const LoopHypothesis& h) {
                                   return h.travelled_m < travelled_m - config_.window_m;
                                 }),
                  accepted_.end());
}

void LoopVerifier::ForgetNode(NodeId id) {
  const auto involves = [id](const LoopHypothesis& h) { return h.old == id || h.current == id; };
  accepted_.erase(std::remove_if(accepted_.begin(), accepted_.end(), involves), accepted_.end());
  stats_.expired += static_cast<int>(std::count_if(pending_.begin(), pending_.end(), involves));
  pending_.erase(std::remove_if(pending_.begin(), pending_.end(), involves), pending_.end());
}

const LoopHypothesis* LoopVerifier::FindPending(NodeId old, NodeId current) const {
  for (const LoopHypothesis& h : pending_) {
    if (h.old == old && h.current == current) return &h;
  }
  return nullptr;
}

bool LoopVerifier::IsPending(NodeId id) const {
  return std::any_of(pending_.begin(), pending_.end(),
                     [id](const LoopHypothesis& h) { return h.old == id || h.current == id; });
}

void LoopVerifier::Accept(const LoopHypothesis& h, std::vector<LoopHypothesis>* out) {
  ++stats_.accepted;
  if (h.injected) ++stats_.injected_accepted;
  accepted_.push_back(h);
  out->push_back(h);
}

namespace {

/// A large clique of the consistency graph `ok` containing `self`, grown greedily: the
/// candidate consistent with the most other candidates joins, until none is left.
std::vector<std::size_t> GreedyClique(const std::vector<std::vector<bool>>& ok, std::size_t self) {
  std::vector<std::size_t> clique{self}, candidates;
  for (std::size_t i = 0; i < ok.size(); ++i) {
    if (i != self && ok[self][i]) candidates.push_back(i);
  }
  while (!candidates.empty()) {
    std::size_t best = candidates.front();
    int best_degree = -1;
    for (std::size_t c : candidates) {
      const int degree = static_cast<int>(std::count_if(candidates.begin(), candidates.end(),
                                                        [&](std::size_t o) { return ok[c][o]; }));
      if (degree > best_degree) {
        best_degree = degree;
        best = c;
      }
    }
    clique.push_back(best);
    candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                    [&](std::size_t o) { return o == best || !ok[best][o]; }),
                     candidates.end());
  }
  return clique;
}

}  // namespace

std::vector<LoopHypothesis> LoopVerifier::Add(const LoopHypothesis& h, const Values& values) {
  ++stats_.proposed;
  if (h.injected) ++stats_.injected;
  std::vector<LoopHypothesis> out;
  if (!config_.enabled) {
    Accept(h, &out);
    return out;
  }
  Expire(h.travelled_m);
  // 1. The accepted closures around h: evidence for it, or against it.
  int support = 0, conflict = 0;
  for (const LoopHypothesis& a : accepted_) (Consistent(h, a, values) ? support : conflict) += 1;
  if (support == 0 && conflict > 0) {
    ++stats_.rejected;
    return out;
  }
  // 2. The largest mutually consistent set containing h (greedy maximum clique) among the
  // pending hypotheses and the accepted closures around h.
  pending_.push_back(h);
  std::vector<const LoopHypothesis*> members;
  for (const LoopHypothesis& p : pending_) members.push_back(&p);
  const std::size_t first_accepted = members.size();
  for (const LoopHypothesis& a : accepted_) members.push_back(&a);
  const std::size_t n = members.size(), self = first_accepted - 1;
  std::vector<std::vector<bool>> ok(n, std::vector<bool>(n, false));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      ok[i][j] = ok[j][i] = Consistent(*members[i], *members[j], values);
    }
  }
  const std::vector<std::size_t> clique = GreedyClique(ok, self);
  if (static_cast<int>(clique.size()) < config_.min_group) return out;
  std::vector<bool> confirmed(first_accepted, false);
  for (std::size_t i : clique) {
    if (i < first_accepted) confirmed[i] = true;
  }
  std::vector<LoopHypothesis> still_pending;
  const std::vector<LoopHypothesis> pool = pending_;
  for (std::size_t i = 0; i < pool.size(); ++i) {
    if (confirmed[i]) {
      Accept(pool[i], &out);
    } else {
      still_pending.push_back(pool[i]);
    }
  }
  pending_ = std::move(still_pending);
  return out;
}

}  // namespace lifelong::slam
