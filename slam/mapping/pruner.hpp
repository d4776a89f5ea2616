// The pruner (seed §5): which node goes (a RemovalPolicy, removal_policy.hpp) and what
// replaces its elimination clique (a Sparsifier, sparsifier.hpp), applied to the pose graph
// with a record of each removal; and the edge budget (PruningConfig::max_edges_per_node),
// which replaces the densest blankets' edges by their Chow-Liu tree. The pruner changes the
// graph only: what the mapper holds of a node (its scans, its cells in the map, its loop
// closures) is the mapper's to move (Mapper::State::RemoveNode).
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include "slam/graph/pose_graph.hpp"
#include "slam/mapping/mapper_config.hpp"
#include "slam/mapping/mapper_records.hpp"
#include "slam/removal/removal_policy.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

/// An edge whose information was scaled for a marginalization, and what it was before.
struct WeighedEdge {
  std::size_t index;  ///< into PoseGraph::edges()
  Eigen::Matrix3d information;
};

/// Scales the information of the robust (loop) edges with both ends in `set` (ascending) by
/// the kernel's IRLS weight rho'(e^T Omega e) at `values`, so a marginalization sees them as
/// the optimizer does (pruning.robust_marginal). Returns what it changed.
std::vector<WeighedEdge> WeighRobustEdges(PoseGraph* graph, const Values& values,
                                          const std::vector<NodeId>& set,
                                          const OptimizerParams& params);

class Pruner {
 public:
  /// The policy and sparsifier of config.mode; std::invalid_argument when either is unknown
  /// (the standard mode has neither).
  Pruner(const PruningConfig& config, const OptimizerParams& optimizer);

  /// Starts a round over the candidates and their gains (bits); `view` shows the scans.
  /// Returns the beams the policy retires (the mapper takes them out of the map).
  std::vector<SampleRetirement> BeginRound(const std::map<NodeId, double>& gains,
                                           const RoundView& view);
  /// The node to remove next among the candidates and their gains (bits), or none.
  std::optional<NodeId> Next(const std::map<NodeId, double>& gains, std::size_t num_nodes) const;
  /// What replaces node `id`'s clique at `values` (its loop edges weighed as the optimizer
  /// weighs them, with pruning.robust_marginal). The graph is left as it was.
  Replacement Marginalize(PoseGraph* graph, const Values& values, NodeId id) const;
  /// Removes node `id` from the graph with its replacement, and records it.
  void Remove(PoseGraph* graph, NodeId id, const Replacement& replacement, double gain_bits);
  /// While the graph holds more than max_edges_per_node edges per node (and the sparsifier
  /// leaves trees), replaces the edges in the Markov blanket (node + neighbours) with the
  /// most edges beyond a tree by their Chow-Liu tree, or, when every blanket is a tree, those
  /// of the two-hop neighbourhood with the most; at most a few per call. `unsettled` gives
  /// the nodes no sparsification may touch.
  void KeepEdgeBudget(PoseGraph* graph, const Values& values,
                      const std::function<std::set<NodeId>()>& unsettled);

  const std::vector<MarginalizationRecord>& marginalizations() const { return removals_; }
  const std::vector<SparsificationRecord>& sparsifications() const { return sparsified_; }

 private:
  PruningConfig config_;
  OptimizerParams optimizer_;
  std::unique_ptr<RemovalPolicy> policy_;
  std::unique_ptr<Sparsifier> sparsifier_;
  std::vector<MarginalizationRecord> removals_;
  std::vector<SparsificationRecord> sparsified_;
};

}  // namespace lifelong::slam
