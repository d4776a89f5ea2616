#include "slam/mapping/scan_store.hpp"

#include <cmath>

namespace lifelong::slam {
std::size_t ScanStore::AddNodeScan(double stamp_s, NodeId node, const Pose2& T_odom_robot) {
  scans_.push_back(Anchored{stamp_s, node, Pose2(), T_odom_robot});
  of_node_[node].push_back(scans_.size() - 1);
  return scans_.size() - 1;
}

void ScanStore::AddPending(double stamp_s, NodeId node, const Pose2& T_node_scan,
                           const Pose2& T_odom_robot, bool measured) {
  scans_.push_back(Anchored{stamp_s, node, T_node_scan, T_odom_robot, measured});
  of_node_[node].push_back(scans_.size() - 1);
  pending_.push_back(scans_.size() - 1);
}

void ScanStore::AnchorPending(NodeId previous, NodeId node, const Pose2& T_odom_node) {
  for (std::size_t idx : pending_) {
    Anchored& a = scans_[idx];
    if (a.anchor != previous || a.measured) continue;
    const Pose2 from_new = Between(T_odom_node, a.T_odom_robot);
    if (Norm(from_new) < Norm(a.T_anchor_scan)) {
      Reanchor(idx, node);
      scans_[idx].T_anchor_scan = from_new;
    }
  }
  pending_.clear();
}

void ScanStore::Handover(NodeId removed, NodeId heir, const Pose2& T_heir_removed) {
  const std::vector<std::size_t> held = of_node_[removed];
  for (std::size_t scan : held) {
    scans_[scan].T_anchor_scan = T_heir_removed * scans_[scan].T_anchor_scan;
    Reanchor(scan, heir);
  }
  of_node_.erase(removed);
}

std::vector<StampedPose> ScanStore::Trajectory(const Values& values) const {
  std::vector<StampedPose> out;
  out.reserve(scans_.size());
  for (const Anchored& a : scans_)
    out.push_back({a.stamp_s, values.at(a.anchor) * a.T_anchor_scan});
  return out;
}

StampedPose ScanStore::Last(const Values& values) const {
  if (scans_.empty()) return {};
  const Anchored& a = scans_.back();
  return {a.stamp_s, values.at(a.anchor) * a.T_anchor_scan};
}

void ScanStore::Reanchor(std::size_t scan, NodeId anchor) {
  auto& old_list = of_node_[scans_[scan].anchor];
  for (std::size_t i = 0; i < old_list.size(); ++i) {
    if (old_list[i] == scan) {
      old_list.erase(old_list.begin() + static_cast<std::ptrdiff_t>(i));
      break;
    }
  }
  scans_[scan].anchor = anchor;
  of_node_[anchor].push_back(scan);
}

}  // namespace lifelong::slam
