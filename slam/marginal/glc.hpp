// Generic linear constraints (GLC; Carlevaris-Bianco, Kaess & Eustice, "Generic Node
// Removal for Factor-Graph SLAM", IEEE T-RO 2014), for SE(2) pose graphs.
//
// Given the exact marginal Lambda_N over the elimination clique N = {r, n_1..n_{m-1}}
// (r = smallest id; marginalization.hpp steps 1-2):
//  1. Root shift (paper §IV-C): express the clique in coordinates relative to r,
//     y_j = e_j = t2v(Z_j^-1 X_r^-1 X_{n_j}), Z_j = X_r^-1 X_{n_j} at the estimate. Lambda_N
//     is gauge free, so its information lives entirely on y: Lambda_y = G^T Lambda_a G,
//     G = blockdiag(J_j^-1) (J_j = de_j/dx_{n_j}), Lambda_a = Lambda_N without r's rows.
//     No prior is added: the root's absolute pose carries no information and is dropped.
//  2. Informative directions (paper §IV-B): Lambda_y = U D U^T; eigenvalues below
//     tolerance * max are dropped, so a low-rank marginal (a partial constraint) yields a
//     factor of that rank, never one made proper by a weak prior.
//  3. Dense GLC: one linear factor over y (a slam::CliqueFactor: its stacked error is y).
//  4. Sparse GLC (paper §IV-D): the Chow-Liu tree of the Gaussian over y_1..y_{m-1} (seed
//     eq. 5.35 mutual information, Kruskal), as one marginal p(y_t) of the tree's root and
//     one conditional p(y_c | y_p) per tree edge. Each becomes a GLC factor: the marginal a
//     factor over {r, n_t} (a relative-pose edge r -> n_t), each conditional a factor over
//     {r, n_p, n_c} with information M_pc - blockdiag(M_p, 0), M the marginal information
//     of (y_p, y_c) (= H^T Lambda_c|p H, H = [-A, I], when Lambda_y is definite; Schur
//     complements with pseudo-inverses keep it exact when it is not). A conditional that
//     does not depend on y_p (an independent pair) becomes a factor over {r, n_c}.
//     Where chow-liu (marginalization.hpp) conditions one node's pose on another's, GLC
//     conditions poses relative to r on each other: its factors are ternary through r.
//     Each factor keeps the directions above tolerance * (largest eigenvalue of Lambda_y),
//     so a conditional of a low-rank Lambda_y that is rounding noise comes out as 0 and is
//     dropped (as iSAM skips a factor with no rank). sparsifier_glc.cpp falls back to the
//     dense factor when the tree misses an informative direction of the marginal.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam {

/// Step 2: U D U^T with eigenvalues below tolerance * max eigenvalue set to 0.
/// *rank (optional) receives the number kept.
Eigen::MatrixXd InformativePart(const Eigen::MatrixXd& lambda, double tolerance,
                                int* rank = nullptr);
/// The same with the cut at tolerance * max(largest eigenvalue, reference): a part of a
/// larger information (a GLC conditional) is judged against the whole (reference = its
/// largest eigenvalue), so a part that is rounding noise comes out as exactly 0.
Eigen::MatrixXd InformativeAbove(const Eigen::MatrixXd& lambda, double tolerance, double reference,
                                 int* rank = nullptr);

/// Steps 1-3: the dense GLC factor (root-shifted, informative part only). For m = 2 with a
/// definite information it is returned as an edge instead (the same error and information).
struct GlcFactors {
  std::vector<PoseEdge> edges;        ///< binary factors r -> n with definite information
  std::vector<CliqueFactor> cliques;  ///< the other factors
};
GlcFactors GlcDense(const std::vector<NodeId>& nodes, const Values& values,
                    const Eigen::MatrixXd& lambda_N, double tolerance);

/// Steps 1, 2 and 4: the Chow-Liu tree of GLC factors. *regularized (optional) is set when
/// the pair weights needed a weak diagonal shift (a low-rank Lambda_y; only the choice of
/// tree uses it, never a factor).
GlcFactors GlcChowLiu(const std::vector<NodeId>& nodes, const Values& values,
                      const Eigen::MatrixXd& lambda_N, double tolerance,
                      bool* regularized = nullptr);

/// KL(p || q) of two gauge-free informations over the same m nodes, with node 0 held, on
/// the range of p (the directions p informs; the usual KL when p is definite there).
/// +inf when q is not definite on that range.
double InformativeKl(const Eigen::MatrixXd& lambda_p, const Eigen::MatrixXd& lambda_q,
                     double tolerance);

}  // namespace lifelong::slam
