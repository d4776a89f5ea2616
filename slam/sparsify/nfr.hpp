// Nonlinear factor recovery (NFR; Mazuran, Tipaldi, Spinello & Burgard, "Nonlinear factor
// recovery for long-term SLAM", IJRR 2016, first at RSS 2014), for SE(2) pose graphs. The
// paper itself was not at hand here: the steps name its ideas, not its equation numbers.
//
// Given the exact marginal Lambda_N over the elimination clique N = {r, n_1..n_{m-1}}
// (r = N[0]; marginalization.hpp steps 1-2) and a topology of pairs of N, NFR finds the
// relative-pose factors on that topology whose Gaussian is closest to the marginal:
//  1. Gauge (as Replacement::kl_divergence): r held, x = the increments of n_1..n_{m-1}
//     (d = 3(m-1)); Sigma = (Lambda_N without r's rows)^-1, the exact marginal covariance.
//  2. Factors (the paper's recovered factors): one relative-pose edge p -> c per pair,
//     measurement X_p^-1 X_c at the estimate (zero residual), error e_i ~ J_i x (J_i: 3 x d,
//     the error Jacobian at the estimate), unknown information Omega_i. Their Gaussian has
//     Lambda(Omega) = sum_i J_i^T Omega_i J_i.
//  3. Objective (the paper's KL objective): minimize KL(N(0, Sigma) || N(0, Lambda^-1)), i.e.
//       f(Omega) = tr(Lambda(Omega) Sigma) - ln|Lambda(Omega)|,  Omega_i PSD,
//     KL = (f - d - ln|Sigma|) / 2, with gradient
//       df/dOmega_i = J_i Sigma J_i^T - J_i Lambda^-1 J_i^T.
//     f is convex in Omega (-ln det of an affine map); the constraint set is a product of
//     PSD cones.
//  4. Tree (the paper's closed form for tree topologies): when the stacked J is square and
//     invertible (m - 1 pairs spanning N) the problem separates: Omega_i =
//     (J_i Sigma J_i^T)^-1, the information of the marginal of edge i's relative pose. For a
//     relative-pose edge this is exactly the pair conditional the chow-liu sparsifier puts on
//     its tree edges (its u_cp is J_c^-1 e_i), so on the same tree NFR and chow-liu coincide
//     (tested): chow-liu's factors are already KL-optimal for their topology.
//  5. Other topologies (Mazuran et al.'s code uses projected quasi-Newton): SolveNfr, a
//     projected Newton method. Variables are whitened per edge, Omega_i = S_i^-1/2 X_i
//     S_i^-1/2 with S_i = J_i Sigma J_i^T, so the tree's solution is X_i = I and the problem
//     is scale free. Projection P: eigenvalue clipping of each X_i (Frobenius-nearest PSD).
//     Each iteration: an epsilon-active set (Bertsekas' two-metric projection method, per
//     eigen-direction: an eigenvalue below min(1e-3, 2 * KKT residual) whose gradient pushes
//     it down is held at 0); the exact Hessian tr(C dLambda C dLambda) (C = Lambda^-1) on the
//     free directions of an orthonormal basis of symmetric 3x3 matrices, plus the curvature
//     the projection adds along rotations of a held direction (without it the steps
//     oscillate near a singular optimum); backtracking (Armijo, 1e-4) along the projected
//     arc t -> P(X + t D); a projected gradient step when Newton finds no decrease or only a
//     negligible one and the gradient step does better.
//     Stopping rule: the KKT residual ||P(X - G) - X||_F (G: whitened gradient; zero exactly
//     at a KKT point of the cone-constrained problem) below kkt_tolerance ("converged");
//     or a step lowering the KL by less than relative_decrease of it; or no step lowering f;
//     or max_iterations. Every accepted step lowers f, so the result is never worse than the
//     start (the tree's solution for nfr-subgraph). An optimum may lie on the cone's
//     boundary: an edge whose best information is singular (PSD, not definite).
// A low-rank marginal (Lambda_N with r held not definite, e.g. partial constraints) is made
// proper by the diagonal shift chow-liu uses (1e-9 of the mean diagonal) and flagged
// `regularized`; NFR then fits that shifted Gaussian (its near-null directions get near-zero
// information). glc.hpp's informative-direction treatment is not carried over.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slam/graph/pose_graph.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

/// Linearized error of one factor over the gauge-fixed x: e ~ J_from x_from + J_to x_to,
/// block index into x (node index in N minus 1), -1 for the held root r.
struct NfrJacobian {
  int from = -1;
  int to = -1;
  Eigen::Matrix3d J_from = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d J_to = Eigen::Matrix3d::Zero();
};

/// Lambda(Omega) = sum_i J_i^T Omega_i J_i, d x d.
Eigen::MatrixXd NfrInformation(const std::vector<NfrJacobian>& jacobians,
                               const std::vector<Eigen::Matrix3d>& information, Eigen::Index d);
/// KL(N(0, sigma) || N(0, Lambda(Omega)^-1)) in nats; +inf when Lambda is not definite.
double NfrKl(const Eigen::MatrixXd& sigma, const std::vector<NfrJacobian>& jacobians,
             const std::vector<Eigen::Matrix3d>& information);
/// df/dOmega_i = J_i Sigma J_i^T - J_i Lambda^-1 J_i^T (f = 2 KL + const; Lambda definite).
std::vector<Eigen::Matrix3d> NfrGradient(const Eigen::MatrixXd& sigma,
                                         const std::vector<NfrJacobian>& jacobians,
                                         const std::vector<Eigen::Matrix3d>& information);
/// Step 4: Omega_i = (J_i Sigma J_i^T)^-1 (the optimum when the pairs form a spanning tree).
std::vector<Eigen::Matrix3d> NfrTreeInformation(const Eigen::MatrixXd& sigma,
                                                const std::vector<NfrJacobian>& jacobians);

struct NfrOptions {
  int max_iterations = 100;
  double kkt_tolerance = 1e-6;       ///< whitened KKT residual (dimensionless)
  double relative_decrease = 1e-12;  ///< stop when a step lowers KL by less than this share
};

struct NfrResult {
  std::vector<Eigen::Matrix3d> information;  ///< Omega_i, PSD
  double kl = 0.0;                           ///< nats, at `information`
  int iterations = 0;                        ///< accepted steps
  double kkt = 0.0;                          ///< whitened KKT residual at the result
  bool converged = false;                    ///< kkt <= kkt_tolerance
};

/// Step 5 from `start` (PSD, Lambda(start) definite; sigma definite). Throws
/// std::invalid_argument when the start is not feasible.
NfrResult SolveNfr(const Eigen::MatrixXd& sigma, const std::vector<NfrJacobian>& jacobians,
                   const std::vector<Eigen::Matrix3d>& start, const NfrOptions& options = {});

// ---- The clique level (used by sparsifier_nfr_*.cpp). ----

/// NFR factors replacing a clique: the Chow-Liu tree over `nodes` (the chow-liu sparsifier's:
/// CliquePairWeights, Kruskal, oriented away from nodes[0]) plus at most `max_extra` of the
/// `candidates` (index pairs into nodes) that are not tree pairs, those with the largest
/// pair weight first (oriented from the smaller index). Without extra pairs the closed form
/// (step 4), else SolveNfr from the tree's solution with the extra edges at 0. An extra edge
/// whose whitened information ends at zero (below 1e-12) is dropped.
struct NfrFactors {
  std::vector<PoseEdge> edges;  ///< kind kMarginal, zero residual at `values`
  bool regularized = false;     ///< Sigma needed the diagonal shift (low-rank marginal)
  NfrResult solver;             ///< what the optimization did (iterations 0 for a tree)
};
NfrFactors RecoverFactors(const std::vector<NodeId>& nodes, const Values& values,
                          const Eigen::MatrixXd& lambda_N,
                          const std::vector<std::pair<std::size_t, std::size_t>>& candidates,
                          std::size_t max_extra, const NfrOptions& options = {});

/// The sparsifiers' common part: k's clique as chow-liu linearizes it (LinearizeAround, with
/// the pose edges among N under BlanketPolicy::kBlanket, which the new edges then replace),
/// Lambda_N by SchurComplementFirstBlock, RecoverFactors with, for `subgraph`, the
/// config.nfr_chords candidates and a budget of floor(config.nfr_chord_ratio * (m - 1))
/// extra edges; KL by GaugeFixedKl; KeepGradientIfAsked.
Replacement NfrReplace(const PoseGraph& graph, const Values& values, NodeId k,
                       const SparsifierConfig& config, bool subgraph);

}  // namespace lifelong::slam
