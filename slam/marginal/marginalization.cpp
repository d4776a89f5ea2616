#include "slam/marginal/marginalization.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "slam/backend/clique_algebra.hpp"
#include "slam/graph/se2.hpp"
#include "slam/marginal/chow_liu.hpp"

namespace lifelong::slam {
namespace {

using clique::At;
using clique::Block;

using Eigen::Matrix3d;
using Eigen::MatrixXd;

/// Relative diagonal shift for a near-singular anchored information (documented flag).
constexpr double kRegularization = 1e-9;

/// Jacobian of e = t2v((X_i^-1 X_j)^-1 X_i^-1 X_j) w.r.t. x_j, i.e. at the current estimate.
Matrix3d JacobianAtEstimate(const Pose2& Xi, const Pose2& Xj) {
  Matrix3d Ji, Jj;
  RelativeErrorJacobians(Xi, Xj, Between(Xi, Xj), &Ji, &Jj);
  return Jj;
}

/// T_ji: a rigid motion that moves node j by dx_j moves node i by T_ji dx_j.
Matrix3d RigidTransfer(const Pose2& Xj, const Pose2& Xi) {
  Matrix3d Ja, Jb;
  RelativeErrorJacobians(Xj, Xi, Between(Xj, Xi), &Ja, &Jb);
  return -Jb.inverse() * Ja;
}

/// SE(2) adjoint for right perturbations: Z * V(e) * Z^-1 = V(Ad(Z) e) to first order.
Matrix3d Adjoint(const Pose2& Z) {
  const double c = std::cos(Z.theta), s = std::sin(Z.theta);
  Matrix3d ad;
  ad << c, -s, Z.y, s, c, -Z.x, 0.0, 0.0, 1.0;
  return ad;
}

MatrixXd Symmetrized(const MatrixXd& m) { return 0.5 * (m + m.transpose()); }

double LogDetSpd(const MatrixXd& m, bool* ok) {
  Eigen::LLT<MatrixXd> llt(m);
  *ok = llt.info() == Eigen::Success;
  if (!*ok) return 0.0;
  return 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
}

/// Inverse of an SPD matrix; adds kRegularization * mean diagonal when LLT fails.
MatrixXd InverseSpd(const MatrixXd& m, bool* regularized) {
  Eigen::LLT<MatrixXd> llt(m);
  if (llt.info() != Eigen::Success) {
    const double shift = kRegularization * std::max(m.trace() / static_cast<double>(m.rows()),
                                                    std::numeric_limits<double>::min());
    llt.compute(m + shift * MatrixXd::Identity(m.rows(), m.cols()));
    *regularized = true;
  }
  return Symmetrized(llt.solve(MatrixXd::Identity(m.rows(), m.cols())));
}

/// Covariance of the increments of all m nodes with node 0 held fixed (rows of 0 are 0).
MatrixXd AnchoredCovariance(const MatrixXd& lambda_N, bool* regularized) {
  const Eigen::Index d = lambda_N.rows() - 3;
  MatrixXd sigma = MatrixXd::Zero(lambda_N.rows(), lambda_N.cols());
  sigma.bottomRightCorner(d, d) = InverseSpd(lambda_N.bottomRightCorner(d, d), regularized);
  return sigma;
}

/// Cov(u_ij), u_ij = dx_i - T_ji dx_j: increment of i relative to j (gauge free).
Matrix3d RelativeCovariance(const MatrixXd& sigma, const std::vector<NodeId>& nodes,
                            const Values& values, std::size_t i, std::size_t j) {
  const Matrix3d T = RigidTransfer(At(values, nodes[j]), At(values, nodes[i]));
  const Matrix3d s_ii = sigma.block<3, 3>(Block(i), Block(i));
  const Matrix3d s_ij = sigma.block<3, 3>(Block(i), Block(j));
  const Matrix3d s_jj = sigma.block<3, 3>(Block(j), Block(j));
  const Matrix3d cov =
      s_ii - T * s_ij.transpose() - s_ij * T.transpose() + T * s_jj * T.transpose();
  return 0.5 * (cov + cov.transpose());
}

double PairWeight(const Matrix3d& relative_cov) {
  const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Matrix3d>(relative_cov).eigenvalues();
  return -0.5 * eig.cwiseMax(std::numeric_limits<double>::min()).array().log().sum();
}

}  // namespace

LocalHessian LinearizeAround(const PoseGraph& graph, const Values& values, NodeId k,
                             BlanketPolicy blanket) {
  LocalHessian out;
  const auto& neighbours = graph.Neighbours(k);
  out.neighbours.assign(neighbours.begin(), neighbours.end());
  std::vector<NodeId> index{k};
  index.insert(index.end(), out.neighbours.begin(), out.neighbours.end());
  out.H = MatrixXd::Zero(Block(index.size()), Block(index.size()));
  for (std::size_t e : graph.EdgesOf(k)) AddEdgeHessian(graph.edges()[e], values, index, &out.H);
  for (std::size_t c : graph.CliquesOf(k)) {
    AddCliqueHessian(graph.cliques()[c], values, index, &out.H);
  }
  if (blanket == BlanketPolicy::kBlanket) {
    for (const PoseEdge& e : graph.EdgesWithin(out.neighbours)) {
      AddEdgeHessian(e, values, index, &out.H);
    }
  }
  return out;
}

MatrixXd SchurComplementFirstBlock(const MatrixXd& H) {
  const Eigen::Index n = H.rows() - 3;
  // H_kk is PSD; a pseudo-inverse keeps the Schur complement exact when k's factors are
  // rank deficient (the range condition holds for PSD H), without regularization.
  Eigen::SelfAdjointEigenSolver<Matrix3d> eig(Matrix3d(H.topLeftCorner<3, 3>()));
  const Eigen::Vector3d values = eig.eigenvalues();
  const double tol = 1e-12 * std::max(values.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::Vector3d inv_values = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) inv_values(i) = values(i) > tol ? 1.0 / values(i) : 0.0;
  const Matrix3d hkk_inv =
      eig.eigenvectors() * inv_values.asDiagonal() * eig.eigenvectors().transpose();
  const MatrixXd h_nk = H.bottomLeftCorner(n, 3);
  return Symmetrized(H.bottomRightCorner(n, n) - h_nk * hkk_inv * h_nk.transpose());
}

CliqueFactor ToCliqueFactor(const std::vector<NodeId>& nodes, const Values& values,
                            const MatrixXd& lambda_N) {
  CliqueFactor clique;
  clique.nodes = nodes;
  const std::size_t k = nodes.size() - 1;
  const Pose2& Xr = At(values, nodes[0]);
  std::vector<Matrix3d> g(k);  // G = blockdiag(J_j^-1)
  for (std::size_t j = 0; j < k; ++j) {
    const Pose2& Xj = At(values, nodes[j + 1]);
    clique.T_root_node.push_back(Between(Xr, Xj));
    g[j] = JacobianAtEstimate(Xr, Xj).inverse();
  }
  // G^T Lambda_a G block by block (O(k^2), not the O(k^3) of dense products).
  MatrixXd info(Block(k), Block(k));
  for (std::size_t a = 0; a < k; ++a) {
    for (std::size_t b = 0; b < k; ++b) {
      info.block<3, 3>(Block(a), Block(b)) =
          g[a].transpose() * lambda_N.block<3, 3>(Block(a + 1), Block(b + 1)) * g[b];
    }
  }
  clique.information = Symmetrized(info);
  return clique;
}

MatrixXd CliquePairWeights(const std::vector<NodeId>& nodes, const Values& values,
                           const MatrixXd& lambda_N) {
  bool regularized = false;
  const MatrixXd sigma = AnchoredCovariance(lambda_N, &regularized);
  const auto m = static_cast<Eigen::Index>(nodes.size());
  MatrixXd w = MatrixXd::Zero(m, m);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t j = i + 1; j < nodes.size(); ++j) {
      const double wij = PairWeight(RelativeCovariance(sigma, nodes, values, i, j));
      w(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = wij;
      w(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i)) = wij;
    }
  }
  return w;
}

double GaugeFixedKl(const MatrixXd& lambda_p, const MatrixXd& lambda_q) {
  const Eigen::Index d = lambda_p.rows() - 3;
  if (d <= 0) return 0.0;
  const MatrixXd p = lambda_p.bottomRightCorner(d, d);
  const MatrixXd q = lambda_q.bottomRightCorner(d, d);
  bool regularized = false, ok_q = false, ok_sigma = false;
  const MatrixXd sigma_p = InverseSpd(p, &regularized);
  const double logdet_p = -LogDetSpd(sigma_p, &ok_sigma);
  const double logdet_q = LogDetSpd(q, &ok_q);
  if (!ok_q || !ok_sigma) return std::numeric_limits<double>::infinity();
  const double kl = 0.5 * ((q * sigma_p).trace() - static_cast<double>(d) + logdet_p - logdet_q);
  return (kl < 0.0 && kl > -1e-9) ? 0.0 : kl;  // rounding only; larger negatives are bugs
}

namespace {

/// Step 4 for any tree: edges p->c with the exact conditionals of the anchored `sigma`.
std::vector<PoseEdge> EdgesFromSigma(const std::vector<NodeId>& nodes, const Values& values,
                                     const MatrixXd& sigma, const std::vector<WeightedPair>& tree) {
  std::vector<PoseEdge> edges;
  for (const TreeEdge& t : OrientTree(static_cast<int>(nodes.size()), tree, 0)) {
    const auto p = static_cast<std::size_t>(t.parent), c = static_cast<std::size_t>(t.child);
    const Pose2& Xp = At(values, nodes[p]);
    const Pose2& Xc = At(values, nodes[c]);
    const Matrix3d cond_info = RelativeCovariance(sigma, nodes, values, c, p).inverse();
    const Matrix3d jc_inv = JacobianAtEstimate(Xp, Xc).inverse();
    PoseEdge edge;
    edge.from = nodes[p];
    edge.to = nodes[c];
    edge.T_from_to = Between(Xp, Xc);
    edge.information = Symmetrized(jc_inv.transpose() * cond_info * jc_inv);
    edge.kind = EdgeKind::kMarginal;
    edges.push_back(edge);
  }
  return edges;
}

// Step 5 for an approximation given as edges over `nodes`: KL(lambda_p || their Hessian).
double EdgesKl(const MatrixXd& lambda_p, const std::vector<PoseEdge>& edges, const Values& values,
               const std::vector<NodeId>& nodes) {
  MatrixXd lambda_q = MatrixXd::Zero(lambda_p.rows(), lambda_p.cols());
  for (const PoseEdge& e : edges) AddEdgeHessian(e, values, nodes, &lambda_q);
  return GaugeFixedKl(lambda_p, lambda_q);
}

/// Steps 3-4: Chow-Liu tree edges over `nodes` (oriented away from nodes[0]).
std::vector<PoseEdge> ChowLiuEdges(const std::vector<NodeId>& nodes, const Values& values,
                                   const MatrixXd& lambda_N, bool* regularized) {
  const MatrixXd sigma = AnchoredCovariance(lambda_N, regularized);
  std::vector<WeightedPair> pairs;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t j = i + 1; j < nodes.size(); ++j) {
      const double w = PairWeight(RelativeCovariance(sigma, nodes, values, i, j));
      pairs.push_back({static_cast<int>(i), static_cast<int>(j), w});
    }
  }
  const int m = static_cast<int>(nodes.size());
  return EdgesFromSigma(nodes, values, sigma, MaximumSpanningTree(m, pairs));
}

}  // namespace

std::vector<PoseEdge> ConditionalTreeEdges(const std::vector<NodeId>& nodes, const Values& values,
                                           const MatrixXd& lambda_N,
                                           const std::vector<WeightedPair>& tree) {
  bool regularized = false;
  return EdgesFromSigma(nodes, values, AnchoredCovariance(lambda_N, &regularized), tree);
}

namespace {

/// A constraint k -> n as (Z_kn, Sigma_kn), Sigma in the right-perturbation error of Z.
struct Spoke {
  NodeId n = 0;
  Pose2 Z_k_n;
  Matrix3d sigma;
  double strength = -std::numeric_limits<double>::infinity();  // ln |Omega|
};

/// The strongest PoseEdge between k and each neighbour (parallel edges beyond it and
/// clique factors are ignored; neighbours joined to k only by cliques get no spoke).
std::vector<Spoke> SpokesOf(const PoseGraph& graph, NodeId k) {
  std::vector<Spoke> spokes;
  for (NodeId n : graph.Neighbours(k)) {
    Spoke best;
    best.n = n;
    for (std::size_t e : graph.EdgesOf(k)) {
      const PoseEdge& edge = graph.edges()[e];
      if (edge.from != n && edge.to != n) continue;
      bool ok = false;
      const double strength = LogDetSpd(edge.information, &ok);
      if (!ok || strength <= best.strength) continue;
      const Matrix3d sigma = edge.information.inverse();
      best.strength = strength;
      if (edge.from == k) {
        best.Z_k_n = edge.T_from_to;
        best.sigma = sigma;
      } else {  // Z_k_n = Z^-1 with error -Ad(Z) e
        best.Z_k_n = edge.T_from_to.Inverse();
        best.sigma = Adjoint(edge.T_from_to) * sigma * Adjoint(edge.T_from_to).transpose();
      }
    }
    if (std::isfinite(best.strength)) spokes.push_back(best);
  }
  return spokes;
}

/// kNaive: hub h = strongest spoke; for every other spoke n, Z_hn = Z_hk Z_kn and
/// Sigma_hn = Ad(Z_kn^-1) Sigma_hk Ad(Z_kn^-1)^T + Sigma_kn (first-order compounding).
std::vector<PoseEdge> NaiveEdges(const PoseGraph& graph, NodeId k) {
  const std::vector<Spoke> spokes = SpokesOf(graph, k);
  if (spokes.size() < 2) return {};
  const Spoke& hub =
      *std::max_element(spokes.begin(), spokes.end(), [](const Spoke& a, const Spoke& b) {
        return a.strength < b.strength;  // first max wins
      });
  const Pose2 Z_h_k = hub.Z_k_n.Inverse();
  const Matrix3d sigma_hk = Adjoint(hub.Z_k_n) * hub.sigma * Adjoint(hub.Z_k_n).transpose();
  std::vector<PoseEdge> edges;
  for (const Spoke& s : spokes) {
    if (s.n == hub.n) continue;
    const Matrix3d ad = Adjoint(s.Z_k_n.Inverse());
    const Matrix3d sigma = ad * sigma_hk * ad.transpose() + s.sigma;
    PoseEdge edge;
    edge.from = hub.n;
    edge.to = s.n;
    edge.T_from_to = Z_h_k * s.Z_k_n;
    edge.information = Symmetrized(sigma.inverse());
    edge.kind = EdgeKind::kMarginal;
    edges.push_back(edge);
  }
  return edges;
}

}  // namespace

namespace {

// What every method shares (steps 1-2 of the header, seed §5.3): the local system at k and,
// for a clique of two or more, its marginal Lambda_N by the Schur complement.
MarginalizationResult Begin(const PoseGraph& graph, const Values& values, NodeId k,
                            BlanketPolicy blanket, MatrixXd* lambda_N) {
  const LocalHessian local = LinearizeAround(graph, values, k, blanket);
  MarginalizationResult result;
  result.neighbours = local.neighbours;
  result.clique_size = local.neighbours.size();
  if (result.clique_size >= 2) *lambda_N = SchurComplementFirstBlock(local.H);
  return result;
}

// A method that leaves pose edges: their pair count and what they lose against Lambda_N.
void FinishEdges(const MatrixXd& lambda_N, const Values& values, MarginalizationResult* result) {
  result->num_pairs = result->edges.size();
  result->kl_divergence = EdgesKl(lambda_N, result->edges, values, result->neighbours);
}

}  // namespace

MarginalizationResult MarginalizeExact(const PoseGraph& graph, const Values& values, NodeId k) {
  MatrixXd lambda_N;
  MarginalizationResult result = Begin(graph, values, k, BlanketPolicy::kFactorsAtK, &lambda_N);
  if (result.clique_size < 2) return result;  // a leaf (or isolated node) just drops out
  result.clique = ToCliqueFactor(result.neighbours, values, lambda_N);
  result.num_pairs = result.clique_size * (result.clique_size - 1) / 2;
  return result;
}

MarginalizationResult MarginalizeChowLiu(const PoseGraph& graph, const Values& values, NodeId k,
                                         BlanketPolicy blanket) {
  MatrixXd lambda_N;
  MarginalizationResult result = Begin(graph, values, k, blanket, &lambda_N);
  if (result.clique_size < 2) return result;
  result.edges = ChowLiuEdges(result.neighbours, values, lambda_N, &result.regularized);
  result.absorbed_blanket = blanket == BlanketPolicy::kBlanket;
  FinishEdges(lambda_N, values, &result);
  return result;
}

MarginalizationResult MarginalizeNaive(const PoseGraph& graph, const Values& values, NodeId k) {
  MatrixXd lambda_N;
  MarginalizationResult result = Begin(graph, values, k, BlanketPolicy::kFactorsAtK, &lambda_N);
  if (result.clique_size < 2) return result;
  result.edges = NaiveEdges(graph, k);
  FinishEdges(lambda_N, values, &result);
  return result;
}

void ApplyMarginalization(PoseGraph* graph, NodeId k, const MarginalizationResult& result) {
  if (result.absorbed_blanket) graph->RemoveEdgesWithin(result.neighbours);
  graph->RemoveNode(k);
  for (const PoseEdge& e : result.edges) graph->AddEdge(e);
  if (result.clique) graph->AddClique(*result.clique);
}

SparsificationResult SparsifyWithin(const PoseGraph& graph, const Values& values,
                                    const std::vector<NodeId>& nodes) {
  SparsificationResult result;
  result.nodes = nodes;
  const std::vector<PoseEdge> within = graph.EdgesWithin(nodes);
  result.edges_before = within.size();
  if (nodes.size() < 2 || within.size() + 1 <= nodes.size()) return result;  // a tree already
  MatrixXd lambda = MatrixXd::Zero(Block(nodes.size()), Block(nodes.size()));
  for (const PoseEdge& e : within) AddEdgeHessian(e, values, nodes, &lambda);
  result.edges = ChowLiuEdges(nodes, values, lambda, &result.regularized);
  result.kl_divergence = EdgesKl(lambda, result.edges, values, nodes);
  result.applied = true;
  return result;
}

void ApplySparsification(PoseGraph* graph, const SparsificationResult& result) {
  if (!result.applied) return;
  graph->RemoveEdgesWithin(result.nodes);
  for (const PoseEdge& e : result.edges) graph->AddEdge(e);
}

}  // namespace lifelong::slam
