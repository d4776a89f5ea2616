// Every scan of the stream, held relative to the graph node that anchors it, so that the
// trajectory follows the graph as it is optimized and survives the removal of nodes
// (DESIGN.md "The mapper as components"). A node's own scan is anchored at it; a scan taken
// between keyframes is anchored at the node before it where the front end refined it against
// the local map, else by odometry at the nearer of the nodes before and after it; a removed
// node hands its scans to a surviving neighbour.
#pragma once

#include <cstddef>
#include <map>
#include <vector>

#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"
#include "types/stamped_pose.hpp"

namespace lifelong::slam {

class ScanStore {
 public:
  /// Node `node`'s own scan; returns its index (the stream's scan count before it).
  std::size_t AddNodeScan(double stamp_s, NodeId node, const Pose2& T_odom_robot);
  /// A scan between keyframes, anchored at `node` by odometry (T_node_scan) until the next
  /// node arrives (AnchorPending); or, `measured` (matched against the table `node` was
  /// matched on: SequentialMatcher::RefineBetween), held at `node` for good.
  void AddPending(double stamp_s, NodeId node, const Pose2& T_node_scan, const Pose2& T_odom_robot,
                  bool measured = false);
  /// A new node (odometry T_odom_node) follows `previous`: each pending scan placed by
  /// odometry goes to whichever of the two is nearer by odometry.
  void AnchorPending(NodeId previous, NodeId node, const Pose2& T_odom_node);
  /// Node `removed` leaves the graph: its scans are held by `heir`, T_heir_removed being the
  /// removed node's pose in the heir's frame.
  void Handover(NodeId removed, NodeId heir, const Pose2& T_heir_removed);

  std::size_t size() const { return scans_.size(); }
  double stamp(std::size_t scan) const { return scans_[scan].stamp_s; }
  /// Every scan's pose at the estimate `values`, in stream order.
  std::vector<StampedPose> Trajectory(const Values& values) const;
  /// Scan `scan`'s pose at `values`.
  Pose2 Pose(std::size_t scan, const Values& values) const {
    return values.at(scans_[scan].anchor) * scans_[scan].T_anchor_scan;
  }
  /// The last scan's pose at `values` (none yet: a default pose).
  StampedPose Last(const Values& values) const;

 private:
  struct Anchored {
    double stamp_s = 0.0;
    NodeId anchor = 0;
    Pose2 T_anchor_scan;
    Pose2 T_odom_robot;
    bool measured = false;  ///< T_anchor_scan was measured, not taken from odometry
  };
  void Reanchor(std::size_t scan, NodeId anchor);

  std::vector<Anchored> scans_;
  std::map<NodeId, std::vector<std::size_t>> of_node_;  ///< the scans each node holds
  std::vector<std::size_t> pending_;  ///< scans since the last node, awaiting the next one
};

}  // namespace lifelong::slam
