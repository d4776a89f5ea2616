// A node's reach, for the approach test (approach_check.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "slam/graph/pose_graph.hpp"
#include "slam/matching/node_data.hpp"

namespace lifelong::slam {

/// Each node's reach: the distance of its farthest point from the robot (m), computed once
/// (a node's points never change). The approach test asks it of every node, to read the
/// points of only those that can reach the two poses.
class NodeReach {
 public:
  double Of(NodeId id, const NodeData& node) {
    const auto found = reach_.find(id);
    if (found != reach_.end()) return found->second;
    double squared = 0.0;
    for (const Eigen::Vector2d& p : node.points) squared = std::max(squared, p.squaredNorm());
    return reach_[id] = std::sqrt(squared);
  }
  void Forget(NodeId id) { reach_.erase(id); }

 private:
  std::unordered_map<NodeId, double> reach_;
};

}  // namespace lifelong::slam
