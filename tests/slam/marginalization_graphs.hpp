// Small graphs for the marginalization and sparsification tests: consistent edges, random
// information matrices and poses, and star-shaped graphs around node 0.
#pragma once

#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slam/graph/pose_graph.hpp"
#include "slam/graph/se2.hpp"

namespace lifelong::slam::test_util {

/// An edge whose measurement agrees with the current estimate (zero residual).
inline PoseEdge ConsistentEdge(NodeId from, NodeId to, const Values& values,
                               const Eigen::Matrix3d& info) {
  PoseEdge e;
  e.from = from;
  e.to = to;
  e.T_from_to = Between(values.at(from), values.at(to));
  e.information = info;
  return e;
}

inline Eigen::Matrix3d RandomInfo(std::mt19937* rng) {
  std::normal_distribution<double> n01(0.0, 1.0);
  Eigen::Matrix3d a;
  for (int i = 0; i < 9; ++i) a(i / 3, i % 3) = n01(*rng);
  return a * a.transpose() + Eigen::Matrix3d::Identity();
}

inline Values RandomValues(const std::vector<NodeId>& ids, std::mt19937* rng) {
  std::uniform_real_distribution<double> xy(-3.0, 3.0), th(-3.0, 3.0);
  Values v;
  for (NodeId id : ids) v[id] = Pose2(xy(*rng), xy(*rng), th(*rng));
  return v;
}

/// k = 0 joined to every neighbour, plus `extra` edges among neighbours (not touching k).
inline PoseGraph Star(const Values& values, const std::vector<NodeId>& neighbours,
                      const std::vector<std::pair<NodeId, NodeId>>& extra, std::mt19937* rng) {
  PoseGraph g;
  for (const auto& [id, pose] : values) g.AddNode(id);
  bool flip = false;
  for (NodeId n : neighbours) {  // alternate directions to exercise both edge orientations
    g.AddEdge(flip ? ConsistentEdge(n, 0, values, RandomInfo(rng))
                   : ConsistentEdge(0, n, values, RandomInfo(rng)));
    flip = !flip;
  }
  for (const auto& [a, b] : extra) g.AddEdge(ConsistentEdge(a, b, values, RandomInfo(rng)));
  return g;
}

}  // namespace lifelong::slam::test_util
