// Marginalizing a node out of the pose graph (seed §5.3, DESIGN.md "Marginalization,
// step by step"). For node k with neighbours N = {n_1..n_m} (ascending ids):
//  1. linearize every factor touching k (PoseEdges and CliqueFactors) at the current
//     estimate into H over [x_k, x_N] (3(m+1) square; block i starts at row 3i);
//  2. exact marginal Lambda_N = H_NN - H_Nk H_kk^-1 H_kN (Schur complement, rank 3m - 3);
//  3. exact: one CliqueFactor over N in root-relative coordinates (root = smallest id):
//     Lambda_y = G^T Lambda_N G, G = [0; blockdiag(J_j^-1)], Z_j = X_r^-1 X_{n_j};
//  4. Chow-Liu: maximum spanning tree of the pairwise mutual information (seed eq. 5.35,
//     Kruskal), each tree edge p->c a PoseEdge with mean X_p^-1 X_c and the conditional
//     information of p(x_c | x_p) mapped into the edge's error: Omega = J_c^-T L_c|p J_c^-1;
//  5. KL(p || q) of the approximation against Lambda_N in the anchored gauge.
//
// Gauge choice for Chow-Liu (step 3). Lambda_N fixes no global frame, so we take seed eq.
// (5.35) in the limit of a vanishing weak prior eps*P (any P > 0). There every pair's MI
// diverges by the same P-dependent constant (3/2 ln(1/eps) + c(P): rigid transfers between
// nodes have unit determinant), and the finite remainder is gauge free:
//     w(i,j) = -1/2 ln |Cov(u_ij)|,   u_ij = dx_i - T_ji dx_j,
// the increment of i relative to j (T_ji: how a rigid motion moving j by dx_j moves i).
// Cov(u_ij) is also lim (S_ii - S_ij S_jj^-1 S_ji) = L_i|j^-1, the conditional used in
// step 4, whose regression on x_j is exactly the rigid transfer, so a relative-pose edge
// represents p(x_c | x_p) exactly. The root enters pairs like any other node. Covariances
// are computed in the anchored gauge (root increment 0, a proper 3(m-1) Gaussian). The
// tree built this way is exact when Lambda_N is tree structured (KL = 0), and has the
// smallest KL of all spanning trees with exact conditionals (both tested).
//
// Naive uses only k's PoseEdges (the strongest per neighbour, by ln|Omega|); clique
// factors at k are dropped and neighbours joined to k only through cliques get no edge.
//
// Means: the new factors take their means from the current estimate (Carlevaris-Bianco &
// Eustice 2014): optimize before marginalizing, residuals at k are ignored.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slam/backend/factor_linearization.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/marginal/chow_liu.hpp"

namespace lifelong::slam {

/// What to add to the graph after graph.RemoveNode(k).
struct MarginalizationResult {
  std::vector<PoseEdge> edges;         ///< kind kMarginal (Chow-Liu, naive)
  std::optional<CliqueFactor> clique;  ///< exact, with m >= 2
  std::size_t clique_size = 0;         ///< m, number of neighbours of k
  std::size_t num_pairs = 0;           ///< pairs kept: m(m-1)/2 for exact, else edges.size()
  double kl_divergence = 0.0;  ///< nats, KL(exact || approximation); 0 for exact; +inf if the
                               ///< approximation leaves the clique disconnected
  bool regularized = false;    ///< a near-singular matrix needed the documented diagonal shift
  /// Markov-blanket sparsification: the pose edges among the neighbours were folded into the
  /// clique's joint before the tree was taken, and ApplyMarginalization removes them.
  bool absorbed_blanket = false;
  std::vector<NodeId> neighbours;  ///< N, ascending
};

/// What a marginalization folds into the clique's Gaussian.
enum class BlanketPolicy {
  kFactorsAtK,  ///< only the factors touching k (DESIGN.md step 1; the other factors stay)
  kBlanket,     ///< also the pose edges among the neighbours, which the tree then replaces,
                ///< so a removal never leaves more than m - 1 edges inside N (Chow-Liu only)
};

// Marginalizing node k (it must exist in graph and values with all its neighbours), one
// function per approximation. A method is chosen once, by its Sparsifier
// (slam/sparsify/sparsifier.hpp), which calls one of these.

/// One dense CliqueFactor over the neighbours: the seed's fill-in (§5.3), lossless.
MarginalizationResult MarginalizeExact(const PoseGraph& graph, const Values& values, NodeId k);
/// The Chow-Liu tree of the clique's marginal as kMarginal PoseEdges (seed §5.4).
MarginalizationResult MarginalizeChowLiu(const PoseGraph& graph, const Values& values, NodeId k,
                                         BlanketPolicy blanket = BlanketPolicy::kFactorsAtK);
/// A star of edges composed through k, from the neighbour with the strongest edge to k
/// (the baseline the seed compares against).
MarginalizationResult MarginalizeNaive(const PoseGraph& graph, const Values& values, NodeId k);

/// graph->RemoveNode(k), then adds result.edges and result.clique.
void ApplyMarginalization(PoseGraph* graph, NodeId k, const MarginalizationResult& result);

/// Chow-Liu sparsification without a removal (this project's extension, used by the pruning
/// edge budget): the pose edges among `nodes` (ascending; they must connect all of them) are
/// one Gaussian over the nodes, which is replaced by its Chow-Liu tree with the exact pair
/// conditionals, as a removal does with its elimination clique under BlanketPolicy::kBlanket.
/// The edges among the nodes go from edges_before to nodes.size() - 1.
struct SparsificationResult {
  std::vector<NodeId> nodes;     ///< ascending
  std::vector<PoseEdge> edges;   ///< the tree, kind kMarginal
  std::size_t edges_before = 0;  ///< pose edges among the nodes before
  double kl_divergence = 0.0;    ///< nats, KL(joint of the old edges || tree), gauge fixed
  bool regularized = false;      ///< see MarginalizationResult
  bool applied = false;          ///< false: the edges already formed a tree (or forest)
};
SparsificationResult SparsifyWithin(const PoseGraph& graph, const Values& values,
                                    const std::vector<NodeId>& nodes);
/// Replaces the pose edges among result.nodes by result.edges (nothing if !result.applied).
void ApplySparsification(PoseGraph* graph, const SparsificationResult& result);

// ---- Building blocks, public for tests and the pruning code. ----

/// Step 1: H over [x_k, x_N], with N = graph.Neighbours(k) ascending.
struct LocalHessian {
  std::vector<NodeId> neighbours;  ///< N, ascending; block i+1 of H is neighbours[i]
  Eigen::MatrixXd H;               ///< 3(m+1) square; block 0 is x_k
};
LocalHessian LinearizeAround(const PoseGraph& graph, const Values& values, NodeId k,
                             BlanketPolicy blanket = BlanketPolicy::kFactorsAtK);

/// Step 2: eliminates the first 3x3 block: H_NN - H_Nk H_kk^-1 H_kN, symmetrized.
Eigen::MatrixXd SchurComplementFirstBlock(const Eigen::MatrixXd& H);

/// Step 3 (kExact): Lambda_N over `nodes` (ascending) as a root-relative CliqueFactor.
CliqueFactor ToCliqueFactor(const std::vector<NodeId>& nodes, const Values& values,
                            const Eigen::MatrixXd& lambda_N);

/// Gauge-free pairwise weights w(i,j) (see the header comment), m x m, zero diagonal.
Eigen::MatrixXd CliquePairWeights(const std::vector<NodeId>& nodes, const Values& values,
                                  const Eigen::MatrixXd& lambda_N);

/// Step 4 for a given spanning tree (pairs index into `nodes`): one kMarginal edge per
/// pair, oriented away from nodes[0], carrying the exact conditional p(x_c | x_p).
std::vector<PoseEdge> ConditionalTreeEdges(const std::vector<NodeId>& nodes, const Values& values,
                                           const Eigen::MatrixXd& lambda_N,
                                           const std::vector<WeightedPair>& tree);

/// Step 5: KL(p || q) of two information matrices over the same m nodes, each with the
/// 3-dim gauge null space, in the gauge where block 0 is held fixed. +inf if q is singular.
double GaugeFixedKl(const Eigen::MatrixXd& lambda_p, const Eigen::MatrixXd& lambda_q);

}  // namespace lifelong::slam
