#include "slam/loops/place_index.hpp"

#include <stdexcept>

#include <nanoflann.hpp>

namespace lifelong::slam {

struct PlaceIndex::Tree {
  using Index =
      nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<float, PlaceIndex>,
                                                 PlaceIndex, -1, std::size_t>;
  Tree(int dims, PlaceIndex& data)
      : index(dims, data, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
  Index index;
};

PlaceIndex::PlaceIndex() = default;
PlaceIndex::~PlaceIndex() = default;

void PlaceIndex::Add(NodeId id, PlaceDescriptor descriptor) {
  if (slot_of_.count(id)) throw std::logic_error("PlaceIndex::Add: node added twice");
  if (!tree_) {
    dims_ = static_cast<int>(descriptor.ring_key.size());
    tree_ = std::make_unique<Tree>(dims_, *this);
  }
  if (descriptor.ring_key.size() != dims_) throw std::logic_error("PlaceIndex::Add: key size");
  const std::size_t slot = keys_.size();
  keys_.push_back(descriptor.ring_key);
  node_of_.push_back(id);
  descriptors_.push_back(std::move(descriptor));
  slot_of_[id] = slot;
  tree_->index.addPoints(slot, slot);
}

void PlaceIndex::Remove(NodeId id) {
  const auto it = slot_of_.find(id);
  if (it == slot_of_.end()) return;
  tree_->index.removePoint(it->second);
  descriptors_[it->second] = PlaceDescriptor{};  // its memory; the slot is never reached again
  slot_of_.erase(it);
}

const PlaceDescriptor& PlaceIndex::Get(NodeId id) const { return descriptors_[slot_of_.at(id)]; }

std::vector<NodeId> PlaceIndex::Nearest(const PlaceDescriptor& query, std::size_t k) const {
  std::vector<NodeId> out;
  if (!tree_ || slot_of_.empty() || k == 0 || query.ring_key.size() != dims_) return out;
  k = std::min(k, slot_of_.size());
  std::vector<std::size_t> slots(k);
  std::vector<float> distances(k);
  nanoflann::KNNResultSet<float, std::size_t> result(k);
  result.init(slots.data(), distances.data());
  tree_->index.findNeighbors(result, query.ring_key.data(), nanoflann::SearchParams());
  for (std::size_t i = 0; i < result.size(); ++i) out.push_back(node_of_[slots[i]]);
  return out;
}

}  // namespace lifelong::slam
