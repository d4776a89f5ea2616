#include "slam/marginal/glc.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "slam/backend/clique_algebra.hpp"
#include "slam/backend/dense_lapack.hpp"
#include "slam/marginal/chow_liu.hpp"
#include "slam/marginal/marginalization.hpp"

namespace lifelong::slam {
namespace {

using clique::Block;
using clique::PinvPsd;

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd Sym(const MatrixXd& m) { return 0.5 * (m + m.transpose()); }

/// Rows/columns of the 3-blocks `vars` of `m`, in that order.
MatrixXd Select(const MatrixXd& m, const std::vector<int>& rows, const std::vector<int>& cols) {
  MatrixXd out(3 * static_cast<Index>(rows.size()), 3 * static_cast<Index>(cols.size()));
  for (std::size_t a = 0; a < rows.size(); ++a) {
    for (std::size_t b = 0; b < cols.size(); ++b) {
      out.block<3, 3>(Block(a), Block(b)) = m.block<3, 3>(3 * rows[a], 3 * cols[b]);
    }
  }
  return out;
}

/// Marginal information of the blocks `keep` of a PSD information (Schur complement with a
/// pseudo-inverse: exact for PSD matrices, no prior).
MatrixXd MarginalInformation(const MatrixXd& lambda, const std::vector<int>& keep) {
  std::vector<int> rest;
  for (int v = 0; v < static_cast<int>(lambda.rows() / 3); ++v) {
    if (std::find(keep.begin(), keep.end(), v) == keep.end()) rest.push_back(v);
  }
  const MatrixXd kk = Select(lambda, keep, keep);
  if (rest.empty()) return kk;
  const MatrixXd kr = Select(lambda, keep, rest);
  return Sym(kk - kr * PinvPsd(Select(lambda, rest, rest)) * kr.transpose());
}

/// Root-shifted information Lambda_y (step 1), via the exact clique's own coordinates.
CliqueFactor RootShifted(const std::vector<NodeId>& nodes, const Values& values,
                         const MatrixXd& lambda_N, double tolerance) {
  CliqueFactor c = ToCliqueFactor(nodes, values, lambda_N);
  c.information = InformativePart(c.information, tolerance);
  return c;
}

/// A factor over {r, n_i (, n_j)} of the root-shifted clique `c` (var = index into y).
CliqueFactor SubFactor(const CliqueFactor& c, const std::vector<int>& vars,
                       const MatrixXd& information) {
  CliqueFactor f;
  f.nodes.push_back(c.nodes[0]);
  for (int v : vars) {
    f.nodes.push_back(c.nodes[static_cast<std::size_t>(v) + 1]);
    f.T_root_node.push_back(c.T_root_node[static_cast<std::size_t>(v)]);
  }
  f.information = information;
  return f;
}

/// Adds a factor, as a relative-pose edge when it is binary with a definite information.
void Emit(const CliqueFactor& f, GlcFactors* out) {
  if (f.information.isZero(0.0)) return;  // no informative direction: no factor (as iSAM)
  if (f.nodes.size() == 2 && f.information.llt().info() == Eigen::Success) {
    PoseEdge e;
    e.from = f.nodes[0];
    e.to = f.nodes[1];
    e.T_from_to = f.T_root_node[0];
    e.information = Sym(f.information);
    e.kind = EdgeKind::kMarginal;
    out->edges.push_back(e);
  } else {
    out->cliques.push_back(f);
  }
}

/// Covariance for the pair weights only: Lambda_y^-1, or with a weak shift when singular.
MatrixXd WeightCovariance(const MatrixXd& lambda_y, bool* regularized) {
  const MatrixXd id = MatrixXd::Identity(lambda_y.rows(), lambda_y.cols());
  Eigen::LLT<MatrixXd> llt(lambda_y);
  if (llt.info() != Eigen::Success) {
    const double scale = std::max(lambda_y.trace() / static_cast<double>(lambda_y.rows()),
                                  std::numeric_limits<double>::min());
    llt.compute(lambda_y + 1e-9 * scale * id);
    if (regularized) *regularized = true;
  }
  return Sym(llt.solve(id));
}

/// ln|S| from eigenvalues clamped at the smallest positive double: a covariance that
/// rounding left barely indefinite still ranks (pair weights only).
double LogDetClamped(const MatrixXd& s) {
  const VectorXd ev = Eigen::SelfAdjointEigenSolver<MatrixXd>(Sym(s)).eigenvalues();
  return ev.cwiseMax(std::numeric_limits<double>::min()).array().log().sum();
}

/// Seed eq. (5.35) for every pair of the 3-blocks of sigma: 1/2 ln(|S_ii||S_jj| / |S_ij,ij|).
std::vector<WeightedPair> PairWeights(const MatrixXd& sigma) {
  const int n = static_cast<int>(sigma.rows() / 3);
  std::vector<double> single;
  for (int i = 0; i < n; ++i) single.push_back(LogDetClamped(Select(sigma, {i}, {i})));
  std::vector<WeightedPair> pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const double joint = LogDetClamped(Select(sigma, {i, j}, {i, j}));
      pairs.push_back({i, j,
                       0.5 * (single[static_cast<std::size_t>(i)] +
                              single[static_cast<std::size_t>(j)] - joint)});
    }
  }
  return pairs;
}

}  // namespace

MatrixXd InformativePart(const MatrixXd& lambda, double tolerance, int* rank) {
  return InformativeAbove(lambda, tolerance, 0.0, rank);
}

MatrixXd InformativeAbove(const MatrixXd& lambda, double tolerance, double reference, int* rank) {
  if (lambda.rows() == 0) return lambda;
  const SymmetricEigen eig = DecomposeSymmetric(Sym(lambda));
  VectorXd ev = eig.values;
  const double cut = tolerance * std::max({ev.maxCoeff(), reference, 0.0});
  int kept = 0;
  for (Index i = 0; i < ev.size(); ++i) {
    if (ev(i) > cut && ev(i) > 0.0) {
      ++kept;
    } else {
      ev(i) = 0.0;
    }
  }
  if (rank) *rank = kept;
  return Sym(eig.vectors * ev.asDiagonal() * eig.vectors.transpose());
}

GlcFactors GlcDense(const std::vector<NodeId>& nodes, const Values& values,
                    const MatrixXd& lambda_N, double tolerance) {
  GlcFactors out;
  if (nodes.size() < 2) return out;
  Emit(RootShifted(nodes, values, lambda_N, tolerance), &out);
  return out;
}

GlcFactors GlcChowLiu(const std::vector<NodeId>& nodes, const Values& values,
                      const MatrixXd& lambda_N, double tolerance, bool* regularized) {
  GlcFactors out;
  if (nodes.size() < 2) return out;
  const CliqueFactor c = RootShifted(nodes, values, lambda_N, tolerance);
  const MatrixXd& lambda_y = c.information;
  const int n = static_cast<int>(nodes.size()) - 1;
  // Directions are informative relative to the clique, not to each factor: a conditional
  // of a low-rank Lambda_y can be pure rounding (~1e-16 of Lambda_y), which a cut relative
  // to its own largest eigenvalue would keep as information (issue #12).
  const double reference =
      Eigen::SelfAdjointEigenSolver<MatrixXd>(lambda_y).eigenvalues().maxCoeff();
  const auto informative = [&](const MatrixXd& m) {
    return InformativeAbove(m, tolerance, reference);
  };
  const MatrixXd sigma = WeightCovariance(lambda_y, regularized);
  const std::vector<TreeEdge> tree = OrientTree(n, MaximumSpanningTree(n, PairWeights(sigma)), 0);
  // The tree's root: its marginal, a factor over {r, n_1}.
  Emit(SubFactor(c, {0}, informative(MarginalInformation(lambda_y, {0}))), &out);
  for (const TreeEdge& t : tree) {
    const MatrixXd m = MarginalInformation(lambda_y, {t.parent, t.child});
    const MatrixXd m_p = m.topLeftCorner<3, 3>() - m.topRightCorner<3, 3>() *
                                                       PinvPsd(m.bottomRightCorner<3, 3>()) *
                                                       m.bottomLeftCorner<3, 3>();
    MatrixXd f = m;
    f.topLeftCorner<3, 3>() -= m_p;
    f = informative(f);
    const bool independent = f.topRows<3>().cwiseAbs().maxCoeff() <= 1e-12 * reference;
    if (independent) {
      Emit(SubFactor(c, {t.child}, f.bottomRightCorner<3, 3>()), &out);
    } else {
      Emit(SubFactor(c, {t.parent, t.child}, f), &out);
    }
  }
  return out;
}

double InformativeKl(const MatrixXd& lambda_p, const MatrixXd& lambda_q, double tolerance) {
  const Index d = lambda_p.rows() - 3;
  if (d <= 0) return 0.0;
  const SymmetricEigen eig = DecomposeSymmetric(Sym(lambda_p.bottomRightCorner(d, d)));
  const VectorXd& ev = eig.values;
  const double cut = tolerance * std::max(ev.maxCoeff(), 0.0);
  std::vector<Index> keep;
  for (Index i = 0; i < ev.size(); ++i) {
    if (ev(i) > cut && ev(i) > 0.0) keep.push_back(i);
  }
  const auto r = static_cast<Index>(keep.size());
  MatrixXd u(d, r);
  VectorXd p_ev(r);
  for (Index i = 0; i < r; ++i) {
    u.col(i) = eig.vectors.col(keep[static_cast<std::size_t>(i)]);
    p_ev(i) = ev(keep[static_cast<std::size_t>(i)]);
  }
  const MatrixXd q = Sym(u.transpose() * lambda_q.bottomRightCorner(d, d) * u);
  Eigen::LLT<MatrixXd> llt(q);
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const double logdet_q = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  const double trace = (q.diagonal().array() / p_ev.array()).sum();
  const double kl = 0.5 * (trace - static_cast<double>(r) + p_ev.array().log().sum() - logdet_q);
  return (kl < 0.0 && kl > -1e-9) ? 0.0 : kl;
}

}  // namespace lifelong::slam
