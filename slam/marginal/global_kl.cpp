#include "slam/marginal/global_kl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "slam/backend/dense_lapack.hpp"
#include "slam/graph/se2.hpp"

namespace lifelong::slam {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Triplets = std::vector<Eigen::Triplet<double>>;

enum class Part { kAnchor, kKept, kRemoved };
struct Slot {
  Part part = Part::kAnchor;
  Index row = 0;  ///< first row of the node's block within its part
};

/// The Hessian at x* split into the dense kept block and the sparse removed blocks.
struct SplitHessian {
  std::map<NodeId, Slot> slots;
  MatrixXd kk;
  Triplets rr, rk;
};

void Scatter(const std::vector<NodeId>& nodes, const MatrixXd& J, const MatrixXd& info,
             SplitHessian* h) {
  const MatrixXd blocks = J.transpose() * info * J;
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    const Slot sa = h->slots.at(nodes[a]);
    for (std::size_t b = 0; b < nodes.size(); ++b) {
      const Slot sb = h->slots.at(nodes[b]);
      const auto ia = static_cast<Index>(3 * a), ib = static_cast<Index>(3 * b);
      if (sa.part == Part::kAnchor || sb.part == Part::kAnchor) continue;
      if (sa.part == Part::kKept && sb.part == Part::kKept) {
        h->kk.block<3, 3>(sa.row, sb.row) += blocks.block<3, 3>(ia, ib);
        continue;
      }
      Triplets* out = sa.part == Part::kRemoved && sb.part == Part::kRemoved ? &h->rr
                      : sa.part == Part::kRemoved && sb.part == Part::kKept  ? &h->rk
                                                                             : nullptr;
      if (!out) continue;  // (kept, removed): the transpose of rk
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c)
          out->emplace_back(sa.row + r, sb.row + c, blocks(ia + r, ib + c));
      }
    }
  }
}

/// Adds every factor of `graph`, linearized at `x`.
void AddGraph(const PoseGraph& graph, const Values& x, SplitHessian* h) {
  for (const PoseEdge& e : graph.edges()) {
    Matrix3d Ji, Jj;
    RelativeErrorJacobians(x.at(e.from), x.at(e.to), e.T_from_to, &Ji, &Jj);
    MatrixXd J(3, 6);
    J << Ji, Jj;
    Scatter({e.from, e.to}, J, e.information, h);
  }
  for (const CliqueFactor& c : graph.cliques()) {
    const std::size_t k = c.nodes.size() - 1;
    MatrixXd J = MatrixXd::Zero(static_cast<Index>(3 * k), static_cast<Index>(3 * (k + 1)));
    for (std::size_t j = 0; j < k; ++j) {
      Matrix3d Jr, Jn;
      RelativeErrorJacobians(x.at(c.nodes[0]), x.at(c.nodes[j + 1]), c.T_root_node[j], &Jr, &Jn);
      J.block<3, 3>(static_cast<Index>(3 * j), 0) = Jr;
      J.block<3, 3>(static_cast<Index>(3 * j), static_cast<Index>(3 * (j + 1))) = Jn;
    }
    Scatter(c.nodes, J, c.information, h);
  }
}

/// Lambda_p = H_KK - H_RK^T H_RR^-1 H_RK, in column chunks to bound memory; takes h->kk.
MatrixXd ExactMarginal(SplitHessian* h, Index removed_rows) {
  MatrixXd lambda = std::move(h->kk);
  if (removed_rows == 0) return lambda;
  const Index d = lambda.rows();
  Eigen::SparseMatrix<double> rr(removed_rows, removed_rows), rk(removed_rows, d);
  rr.setFromTriplets(h->rr.begin(), h->rr.end());
  rk.setFromTriplets(h->rk.begin(), h->rk.end());
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(rr);
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error("GlobalKlDivergence: removed nodes not tied to the kept ones");
  }
  constexpr Index kChunk = 256;
  for (Index c0 = 0; c0 < d; c0 += kChunk) {
    const Index w = std::min(kChunk, d - c0);
    const MatrixXd x = llt.solve(MatrixXd(rk.middleCols(c0, w)));
    lambda.middleCols(c0, w) -= rk.transpose() * x;
  }
  return lambda;  // CholeskyInPlace reads its lower triangle only
}

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

GlobalKl GlobalKlDivergence(const PoseGraph& full, const Values& full_optimum,
                            const PoseGraph& sparse, const Values& sparse_optimum) {
  const std::vector<NodeId> kept = sparse.NodeIds();
  if (kept.empty()) throw std::invalid_argument("GlobalKlDivergence: no kept node");
  SplitHessian hp, hq;
  Index kept_rows = 0, removed_rows = 0;
  for (NodeId id : full.NodeIds()) {
    Slot s;
    if (id == kept.front()) {
      s.part = Part::kAnchor;
    } else if (sparse.HasNode(id)) {
      s = {Part::kKept, kept_rows};
      kept_rows += 3;
    } else {
      s = {Part::kRemoved, removed_rows};
      removed_rows += 3;
    }
    hp.slots[id] = s;
  }
  for (NodeId id : kept) {
    if (!full.HasNode(id)) throw std::invalid_argument("GlobalKlDivergence: unknown kept node");
    hq.slots[id] = hp.slots.at(id);
  }
  GlobalKl out;
  out.dimension = static_cast<std::size_t>(kept_rows);
  hp.kk = hq.kk = MatrixXd::Zero(kept_rows, kept_rows);
  AddGraph(full, full_optimum, &hp);
  AddGraph(sparse, full_optimum, &hq);
  // delta: the sparsified optimum moved rigidly onto the anchor of x*.
  const Pose2 T = full_optimum.at(kept.front()) * sparse_optimum.at(kept.front()).Inverse();
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(kept_rows);
  double sum_sq = 0.0;
  for (NodeId id : kept) {
    const Pose2 q = T * sparse_optimum.at(id);
    const Pose2& p = full_optimum.at(id);
    sum_sq += (q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y);
    const Slot s = hq.slots.at(id);
    if (s.part == Part::kKept)
      delta.segment<3>(s.row) << q.x - p.x, q.y - p.y, WrapAngle(q.theta - p.theta);
  }
  out.rms_offset_m = std::sqrt(sum_sq / static_cast<double>(kept.size()));
  if (kept_rows == 0) return out;
  // In place, two d x d matrices at a time (dense_lapack.hpp): L_p, L_q, then L_p^-1 L_q.
  MatrixXd lp = ExactMarginal(&hp, removed_rows);
  MatrixXd lq = std::move(hq.kk);
  out.mean_term = 0.5 * delta.dot(lq.selfadjointView<Eigen::Lower>() * delta);
  if (!CholeskyInPlace(&lp)) {
    throw std::runtime_error("GlobalKlDivergence: the full graph's marginal is singular");
  }
  if (!CholeskyInPlace(&lq)) {
    out.kl = std::numeric_limits<double>::infinity();
    return out;
  }
  const double logdet_p = 2.0 * lp.diagonal().array().log().sum();
  const double logdet_q = 2.0 * lq.diagonal().array().log().sum();
  // tr(Lambda_q Lambda_p^-1) = |L_p^-1 L_q|_F^2 with Lambda = L L^T.
  SolveLowerInPlace(lp, &lq);
  const double trace = lq.squaredNorm();
  out.kl = 0.5 * (trace - static_cast<double>(kept_rows) + logdet_p - logdet_q) + out.mean_term;
  return out;
}

}  // namespace lifelong::slam
