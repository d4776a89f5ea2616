// Pose graph: the factors (relative-pose edges and dense marginal cliques) over SE(2)
// nodes. The estimate (Values) and the optimizer are separate objects (GTSAM style).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include <Eigen/Core>

#include "sensor/pose2.hpp"
#include "types/pose_factors.hpp"

namespace lifelong::slam {

// The factor types are plain data shared with io (types/pose_factors.hpp).
using lifelong::CliqueFactor;
using lifelong::NodeId;
using lifelong::PoseEdge;
using lifelong::PoseFactors;
using lifelong::Values;

/// The graph's factors plus adjacency. Node ids are stable and never reused.
class PoseGraph {
 public:
  /// The graph of `factors`: its nodes, then its edges and cliques in their order. Throws
  /// std::logic_error as AddNode, AddEdge and AddClique do.
  static PoseGraph FromFactors(const PoseFactors& factors);
  /// The nodes (ascending ids), edges and cliques, as FromFactors takes them.
  PoseFactors Factors() const;
  void AddNode(NodeId id);
  bool HasNode(NodeId id) const { return adjacency_.count(id) != 0; }
  /// Adds an edge; both nodes must exist. Returns its index into edges().
  std::size_t AddEdge(const PoseEdge& edge);
  std::size_t AddClique(const CliqueFactor& clique);
  /// Removes a node and every edge and clique factor touching it (no marginalization:
  /// that is the caller's job, see marginalization.hpp).
  void RemoveNode(NodeId id);
  /// The pose edges with both ends in `nodes` (ascending ids).
  std::vector<PoseEdge> EdgesWithin(const std::vector<NodeId>& nodes) const;
  /// Removes the pose edges with both ends in `nodes` (ascending ids).
  void RemoveEdgesWithin(const std::vector<NodeId>& nodes);
  /// The clique factors with every node in `nodes` (ascending ids).
  std::vector<CliqueFactor> CliquesWithin(const std::vector<NodeId>& nodes) const;
  /// Removes the clique factors with every node in `nodes` (ascending ids).
  void RemoveCliquesWithin(const std::vector<NodeId>& nodes);

  const std::vector<PoseEdge>& edges() const { return edges_; }
  /// Replaces the information of edges()[index] (its measurement and nodes stay).
  void SetEdgeInformation(std::size_t index, const Eigen::Matrix3d& information);
  const std::vector<CliqueFactor>& cliques() const { return cliques_; }
  std::size_t NumNodes() const { return adjacency_.size(); }
  /// Edges counted as for the gamma index: each PoseEdge once, each clique factor over
  /// m nodes as its m(m-1)/2 pairs (DESIGN.md).
  std::size_t NumEdgesForGamma() const;
  /// gamma = e / (v (v - 1) / 2); 0 for fewer than two nodes.
  double Gamma() const;
  /// Node ids in ascending order.
  std::vector<NodeId> NodeIds() const;
  /// Nodes sharing an edge or clique with `id`.
  const std::set<NodeId>& Neighbours(NodeId id) const;
  /// Indices into edges() of the edges touching `id`.
  std::vector<std::size_t> EdgesOf(NodeId id) const;
  /// Indices into cliques() of the clique factors touching `id`.
  std::vector<std::size_t> CliquesOf(NodeId id) const;
  /// Approximate heap bytes held by the graph's factors and adjacency.
  std::size_t Bytes() const;

 private:
  /// Counts one more (or one fewer) factor joining a and b, both ways; adjacency_ holds
  /// the pairs whose count is positive. Keeps removals local: O(factor size x log n).
  void Link(NodeId a, NodeId b);
  void Unlink(NodeId a, NodeId b);
  void LinkFactor(const std::vector<NodeId>& nodes, bool link);
  std::map<NodeId, std::set<NodeId>> adjacency_;
  std::map<NodeId, std::map<NodeId, int>> link_count_;  ///< factors joining each pair
  std::vector<PoseEdge> edges_;
  std::vector<CliqueFactor> cliques_;
};

}  // namespace lifelong::slam
