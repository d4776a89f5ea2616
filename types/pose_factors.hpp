// A pose graph's factors as plain data: what a graph file holds and what the mapper's
// PoseGraph (slam/graph/pose_graph.hpp) is built from and hands back. io reads and writes
// these, so it needs no part of slam.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include <Eigen/Core>

#include "sensor/pose2.hpp"
#include "types/edge_kind.hpp"

namespace lifelong {

using NodeId = std::int64_t;

/// An estimate: one pose per node, T_world_node.
using Values = std::map<NodeId, Pose2>;

/// Relative-pose constraint Z = T_from_to with information Omega (3x3, order x, y, theta).
/// Error (DESIGN.md):  e = t2v(Z^-1 * (X_from^-1 * X_to)).
struct PoseEdge {
  NodeId from = 0;
  NodeId to = 0;
  Pose2 T_from_to;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  EdgeKind kind = EdgeKind::kOdometry;
  bool robust = false;  ///< apply the optimizer's robust kernel (loop closures)
};

/// A dense factor over a clique, as left by exact marginalization (seed §5.3), in
/// root-relative coordinates (Carlevaris-Bianco's generic linear constraint): for
/// nodes = {r, n_1..n_k} it stacks e_j = t2v(Z_j^-1 * (X_r^-1 * X_{n_j})), j = 1..k,
/// with one dense 3k x 3k information over the stacked error. Block j starts at row 3(j-1).
struct CliqueFactor {
  std::vector<NodeId> nodes;       ///< nodes[0] is the root r
  std::vector<Pose2> T_root_node;  ///< Z_j for nodes[1..], size nodes.size() - 1
  Eigen::MatrixXd information;     ///< 3k x 3k, symmetric positive (semi)definite
};

/// A graph's nodes and factors, in the order they were read or added.
struct PoseFactors {
  std::vector<NodeId> nodes;
  std::vector<PoseEdge> edges;
  std::vector<CliqueFactor> cliques;
};

}  // namespace lifelong
