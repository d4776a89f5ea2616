// The offline sparsification protocol of the literature (DESIGN.md "Methods as parts";
// Carlevaris-Bianco et al. 2014, Mazuran et al. 2016): with the full graph at its optimum x*,
// remove nodes one at a time in ascending id order, each time replacing the node's
// elimination clique by a sparsifier's factors, every factor linearized at x*.
#pragma once

#include <cstddef>
#include <vector>

#include "slam/graph/pose_graph.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

/// The ids (ascending) to remove so that round(keep_share * n) nodes stay (at least one),
/// spread evenly over `ids` (ascending): kept are ids[floor(i * n / kept)], i = 0..kept-1,
/// so the first node is always kept. keep_share must be in (0, 1].
std::vector<NodeId> RemovalForKeepShare(const std::vector<NodeId>& ids, double keep_share);

struct OfflineSparsifyStats {
  std::size_t removed = 0;
  double time_s = 0.0;          ///< wall time of the removals alone
  double local_kl_sum = 0.0;    ///< nats, sum of the per-clique KL the sparsifier reported
  std::size_t regularized = 0;  ///< removals that needed a documented diagonal shift
  std::size_t max_clique = 0;   ///< largest elimination clique met (neighbours of a node)
};

/// Removes `remove` (any order; done ascending, or connected set by connected set for a
/// sparsifier that ReplacesSets) from *graph with `sparsifier`; `values` is
/// the estimate every factor is linearized at (not changed). Each id must be a node.
OfflineSparsifyStats SparsifyOffline(PoseGraph* graph, const Values& values,
                                     std::vector<NodeId> remove, const Sparsifier& sparsifier);

}  // namespace lifelong::slam
