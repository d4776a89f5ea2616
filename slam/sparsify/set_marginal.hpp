// The exact marginal left by removing a connected set of nodes at once. Eliminating nodes one
// at a time, each time replacing the factors at the node by the exact Schur complement of its
// clique, gives in the end, for every connected set S of removed nodes, one factor over S's
// boundary B (the kept nodes sharing a factor with S):
//   Lambda_B = H_BB - H_BS H_SS^-1 H_SB,   g_B = g_B - H_BS H_SS^-1 g_S,
// where H and g are the Hessian and gradient, at the estimate, of the factors touching S.
// The Schur complement does not depend on the order of elimination, so one sparse Cholesky
// factorization of H_SS (CHOLMOD) gives what |S| dense eliminations over ever larger
// cliques would, up to rounding: city10000 at keep share 0.25 removes a connected set of
// 6693 nodes bounded by 2367 kept ones. Used by the methods whose result is exact
// (Sparsifier::ReplaceSet).
#pragma once

#include <optional>
#include <vector>

#include "slam/graph/pose_graph.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

/// The connected sets of `remove` (ascending, each a node of `graph`), joined by the edges
/// and clique factors among them; each set ascending, the sets ordered by their first id.
std::vector<std::vector<NodeId>> ConnectedSets(const PoseGraph& graph,
                                               const std::vector<NodeId>& remove);

/// The exact marginal over the boundary of `set` (ascending), of the factors touching it and,
/// with `within_boundary`, of the factors among the boundary too. nullopt when the set has
/// fewer than two boundary nodes or H_SS is not positive definite (a node of the set that
/// the factors do not pin down); then eliminating one node at a time is the way.
struct SetMarginal {
  std::vector<NodeId> boundary;  ///< B, ascending
  CliqueMarginal marginal;       ///< Lambda_B and g_B, blocks in the order of `boundary`
};
std::optional<SetMarginal> MarginalizeSet(const PoseGraph& graph, const Values& values,
                                          const std::vector<NodeId>& set, bool within_boundary);

/// Removes every node of `set` (and the factors among the boundary r absorbed), then adds
/// r's factors: the set counterpart of ApplyReplacement.
void ApplySetReplacement(PoseGraph* graph, const std::vector<NodeId>& set, const Replacement& r);

}  // namespace lifelong::slam
