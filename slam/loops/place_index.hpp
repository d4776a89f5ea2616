// The places of the graph's nodes, searchable by ring key (slam/loops/place_descriptor.hpp): a
// k-d tree (nanoflann's dynamic index) over the keys, to which nodes are added as they are
// made and from which they are removed with them.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include "slam/graph/pose_graph.hpp"
#include "slam/loops/place_descriptor.hpp"

namespace lifelong::slam {

class PlaceIndex {
 public:
  PlaceIndex();
  ~PlaceIndex();
  PlaceIndex(const PlaceIndex&) = delete;
  PlaceIndex& operator=(const PlaceIndex&) = delete;

  void Add(NodeId id, PlaceDescriptor descriptor);
  void Remove(NodeId id);
  bool Contains(NodeId id) const { return slot_of_.count(id) > 0; }
  const PlaceDescriptor& Get(NodeId id) const;
  std::size_t size() const { return slot_of_.size(); }

  /// Up to k nodes whose ring keys are nearest the query's (Euclidean), nearest first.
  std::vector<NodeId> Nearest(const PlaceDescriptor& query, std::size_t k) const;

  // nanoflann's dataset interface (over slots; removed slots stay, unreachable).
  std::size_t kdtree_get_point_count() const { return keys_.size(); }
  float kdtree_get_pt(std::size_t slot, std::size_t dim) const { return keys_[slot](dim); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }

 private:
  struct Tree;
  std::vector<Eigen::VectorXf> keys_;         // by slot
  std::vector<NodeId> node_of_;               // by slot
  std::vector<PlaceDescriptor> descriptors_;  // by slot
  std::map<NodeId, std::size_t> slot_of_;
  std::unique_ptr<Tree> tree_;
  int dims_ = 0;
};

}  // namespace lifelong::slam
