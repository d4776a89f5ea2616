// A node's reach, for the approach test (approach_check.hpp).
#pragma once

#include <unordered_map>

#include "slam/graph/pose_graph.hpp"
#include "slam/matching/node_data.hpp"

namespace lifelong::slam {

/// Each node's reach: the distance of its farthest point from the robot (m), computed once
/// (a node's points never change). The approach test asks it of every node, to read the
/// points of only those that can reach the two poses.
class NodeReach {
 public:
  double Of(NodeId id, const NodeData& node);
  void Forget(NodeId id) { reach_.erase(id); }

 private:
  std::unordered_map<NodeId, double> reach_;
};

}  // namespace lifelong::slam
