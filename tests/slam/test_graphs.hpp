// Small pose graphs built by hand, for the back-end's tests.
#pragma once

#include <Eigen/Core>

#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam::test {

constexpr double kPi = 3.14159265358979323846;

inline PoseEdge Edge(NodeId from, NodeId to, const Pose2& z, const Eigen::Matrix3d& info) {
  PoseEdge e;
  e.from = from;
  e.to = to;
  e.T_from_to = z;
  e.information = info;
  return e;
}

/// A graph of nodes 0..n-1 and no factor.
inline PoseGraph Nodes(int n) {
  PoseGraph g;
  for (int i = 0; i < n; ++i) g.AddNode(i);
  return g;
}

}  // namespace lifelong::slam::test
