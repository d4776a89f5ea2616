// Graph searches from the current node (seed §4.3 and §5.1):
//  - Dijkstra projection of covariances (Tipaldi et al. 2007): the uncertainty of every
//    node relative to the source, compounded along the most certain path. Loop-closure
//    candidates are the nodes whose poses lie inside the current pose's uncertainty.
//  - Dijkstra expansion by path length: the nodes recorded near the current location,
//    the neighbourhood the pruning considers.
#pragma once

#include <map>

#include <Eigen/Core>

#include "slam/graph/clique_links.hpp"
#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam {

struct ProjectedNode {
  Eigen::Matrix3d covariance;  ///< of the node's pose relative to the source, world-aligned
  double path_length_m = 0.0;  ///< length of the chosen path on the current estimate
  int hops = 0;
};

struct ProjectionConfig {
  double max_position_sigma_m = 10.0;  ///< stop expanding past this 1-sigma position error
  double max_path_length_m = 1e9;      ///< stop expanding past this path length
};

/// Dijkstra projection from `source`, ordered by the trace of the position covariance.
/// Each edge compounds  Sigma_v = A Sigma_u A^T + B C_e B^T  with C_e = Omega^-1, A and B
/// the Jacobians of X_v = X_u * Z with respect to X_u and to Z (Z at the current estimate).
/// Clique factors give links by group (clique_links.hpp); `cache` (optional) keeps the
/// groups' covariances for the next call.
std::map<NodeId, ProjectedNode> ProjectCovariances(const PoseGraph& graph, const Values& values,
                                                   NodeId source,
                                                   const ProjectionConfig& config = {},
                                                   CliqueGroupCache* cache = nullptr);

/// Dijkstra expansion from `source` by path length over the current estimate; returns each
/// reached node with its path length (m), up to `max_path_length_m`.
std::map<NodeId, double> ExpandByPathLength(const PoseGraph& graph, const Values& values,
                                            NodeId source, double max_path_length_m);

/// Whether the graph is connected (every node reachable from the first).
bool IsConnected(const PoseGraph& graph);

}  // namespace lifelong::slam
