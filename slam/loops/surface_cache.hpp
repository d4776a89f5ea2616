// A bounded cache of the nodes' loop-closing reference points (surface points in the robot
// frame, SurfacePoints). Consecutive loop-closing attempts build their submaps from mostly
// the same nodes, whose points depend on the scan alone, so recomputing them per attempt
// was a fifth of loop closing (docs/results.md "Exact speed-ups"). LRU entries go first, so the
// cache holds the neighbourhood being revisited, whatever the length of the run. Internal
// to slam.
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam {

class SurfaceCache {
 public:
  explicit SurfaceCache(std::size_t capacity) : capacity_(capacity) {}

  /// The points of node `id`, from `make()` the first time (or after eviction). The reference
  /// stays valid until the next call.
  template <typename Make>
  const std::vector<Eigen::Vector2d>& Get(NodeId id, Make&& make) {
    ++clock_;
    const auto found = entries_.find(id);
    if (found != entries_.end()) {
      found->second.used = clock_;
      ++hits_;
      return found->second.points;
    }
    ++misses_;
    if (entries_.size() >= capacity_) Evict();
    Entry& entry = entries_[id];
    entry.points = std::forward<Make>(make)();
    entry.used = clock_;
    return entry.points;
  }
  /// Forgets a node (removed from the graph).
  void Erase(NodeId id) { entries_.erase(id); }
  std::size_t size() const { return entries_.size(); }
  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }

 private:
  struct Entry {
    std::vector<Eigen::Vector2d> points;
    std::uint64_t used = 0;
  };
  void Evict() {
    auto oldest = entries_.begin();
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if (it->second.used < oldest->second.used) oldest = it;
    }
    if (oldest != entries_.end()) entries_.erase(oldest);
  }

  std::size_t capacity_;
  std::uint64_t clock_ = 0, hits_ = 0, misses_ = 0;
  std::unordered_map<NodeId, Entry> entries_;
};

}  // namespace lifelong::slam
