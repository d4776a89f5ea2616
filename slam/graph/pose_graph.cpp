#include "slam/graph/pose_graph.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>

namespace lifelong::slam {

PoseGraph PoseGraph::FromFactors(const PoseFactors& factors) {
  PoseGraph graph;
  for (NodeId id : factors.nodes) graph.AddNode(id);
  for (const PoseEdge& edge : factors.edges) graph.AddEdge(edge);
  for (const CliqueFactor& clique : factors.cliques) graph.AddClique(clique);
  return graph;
}

PoseFactors PoseGraph::Factors() const { return {NodeIds(), edges_, cliques_}; }

void PoseGraph::AddNode(NodeId id) {
  if (!adjacency_.emplace(id, std::set<NodeId>{}).second ||
      !link_count_.emplace(id, std::map<NodeId, int>{}).second) {
    throw std::logic_error("PoseGraph::AddNode: duplicate node id " + std::to_string(id));
  }
}

std::size_t PoseGraph::AddEdge(const PoseEdge& edge) {
  if (!HasNode(edge.from) || !HasNode(edge.to) || edge.from == edge.to) {
    throw std::logic_error("PoseGraph::AddEdge: bad endpoints " + std::to_string(edge.from) +
                           " -> " + std::to_string(edge.to));
  }
  edges_.push_back(edge);
  Link(edge.from, edge.to);
  return edges_.size() - 1;
}

std::size_t PoseGraph::AddClique(const CliqueFactor& clique) {
  const std::size_t k = clique.nodes.size();
  if (k < 2 || clique.T_root_node.size() != k - 1 ||
      clique.information.rows() != static_cast<Eigen::Index>(3 * (k - 1)) ||
      clique.information.cols() != clique.information.rows()) {
    throw std::logic_error("PoseGraph::AddClique: inconsistent clique dimensions");
  }
  for (NodeId n : clique.nodes) {
    if (!HasNode(n)) throw std::logic_error("PoseGraph::AddClique: unknown node");
  }
  cliques_.push_back(clique);
  LinkFactor(clique.nodes, true);
  return cliques_.size() - 1;
}

void PoseGraph::RemoveNode(NodeId id) {
  if (!HasNode(id)) throw std::logic_error("PoseGraph::RemoveNode: unknown node");
  // In place and order-preserving: indices of the factors that stay keep their order.
  edges_.erase(std::remove_if(edges_.begin(), edges_.end(),
                              [&](const PoseEdge& e) {
                                if (e.from != id && e.to != id) return false;
                                Unlink(e.from, e.to);
                                return true;
                              }),
               edges_.end());
  cliques_.erase(
      std::remove_if(cliques_.begin(), cliques_.end(),
                     [&](const CliqueFactor& c) {
                       if (std::find(c.nodes.begin(), c.nodes.end(), id) == c.nodes.end()) {
                         return false;
                       }
                       LinkFactor(c.nodes, false);
                       return true;
                     }),
      cliques_.end());
  adjacency_.erase(id);
  link_count_.erase(id);
}

std::vector<PoseEdge> PoseGraph::EdgesWithin(const std::vector<NodeId>& nodes) const {
  auto in = [&](NodeId n) { return std::binary_search(nodes.begin(), nodes.end(), n); };
  std::vector<PoseEdge> out;
  for (const PoseEdge& e : edges_) {
    if (in(e.from) && in(e.to)) out.push_back(e);
  }
  return out;
}

void PoseGraph::SetEdgeInformation(std::size_t index, const Eigen::Matrix3d& information) {
  edges_.at(index).information = information;
}

void PoseGraph::RemoveEdgesWithin(const std::vector<NodeId>& nodes) {
  auto in = [&](NodeId n) { return std::binary_search(nodes.begin(), nodes.end(), n); };
  edges_.erase(std::remove_if(edges_.begin(), edges_.end(),
                              [&](const PoseEdge& e) {
                                if (!in(e.from) || !in(e.to)) return false;
                                Unlink(e.from, e.to);
                                return true;
                              }),
               edges_.end());
}

namespace {
bool CliqueWithin(const CliqueFactor& c, const std::vector<NodeId>& nodes) {
  return std::all_of(c.nodes.begin(), c.nodes.end(),
                     [&](NodeId n) { return std::binary_search(nodes.begin(), nodes.end(), n); });
}
}  // namespace

std::vector<CliqueFactor> PoseGraph::CliquesWithin(const std::vector<NodeId>& nodes) const {
  std::vector<CliqueFactor> out;
  for (const CliqueFactor& c : cliques_) {
    if (CliqueWithin(c, nodes)) out.push_back(c);
  }
  return out;
}

void PoseGraph::RemoveCliquesWithin(const std::vector<NodeId>& nodes) {
  cliques_.erase(std::remove_if(cliques_.begin(), cliques_.end(),
                                [&](const CliqueFactor& c) {
                                  if (!CliqueWithin(c, nodes)) return false;
                                  LinkFactor(c.nodes, false);
                                  return true;
                                }),
                 cliques_.end());
}

void PoseGraph::Link(NodeId a, NodeId b) {
  if (link_count_[a][b]++ == 0) adjacency_[a].insert(b);
  if (link_count_[b][a]++ == 0) adjacency_[b].insert(a);
}

void PoseGraph::Unlink(NodeId a, NodeId b) {
  const auto drop = [this](NodeId from, NodeId to) {
    auto row = link_count_.find(from);
    if (row == link_count_.end()) return;  // `from` is being removed
    auto it = row->second.find(to);
    assert(it != row->second.end() && it->second > 0);
    if (--it->second == 0) {
      row->second.erase(it);
      adjacency_[from].erase(to);
    }
  };
  drop(a, b);
  drop(b, a);
}

void PoseGraph::LinkFactor(const std::vector<NodeId>& nodes, bool link) {
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t j = i + 1; j < nodes.size(); ++j) {
      if (nodes[i] == nodes[j]) continue;
      if (link) {
        Link(nodes[i], nodes[j]);
      } else {
        Unlink(nodes[i], nodes[j]);
      }
    }
  }
}

std::size_t PoseGraph::NumEdgesForGamma() const {
  std::size_t n = edges_.size();
  for (const CliqueFactor& c : cliques_) n += c.nodes.size() * (c.nodes.size() - 1) / 2;
  return n;
}

double PoseGraph::Gamma() const {
  const double v = static_cast<double>(NumNodes());
  if (v < 2.0) return 0.0;
  return static_cast<double>(NumEdgesForGamma()) / (v * (v - 1.0) / 2.0);
}

std::vector<NodeId> PoseGraph::NodeIds() const {
  std::vector<NodeId> ids;
  ids.reserve(adjacency_.size());
  for (const auto& [id, unused] : adjacency_) ids.push_back(id);
  return ids;
}

const std::set<NodeId>& PoseGraph::Neighbours(NodeId id) const {
  auto it = adjacency_.find(id);
  if (it == adjacency_.end()) throw std::logic_error("PoseGraph::Neighbours: unknown node");
  return it->second;
}

std::vector<std::size_t> PoseGraph::EdgesOf(NodeId id) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    if (edges_[i].from == id || edges_[i].to == id) out.push_back(i);
  }
  return out;
}

std::vector<std::size_t> PoseGraph::CliquesOf(NodeId id) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < cliques_.size(); ++i) {
    for (NodeId n : cliques_[i].nodes) {
      if (n == id) {
        out.push_back(i);
        break;
      }
    }
  }
  return out;
}

std::size_t PoseGraph::Bytes() const {
  std::size_t bytes = sizeof(*this) + edges_.capacity() * sizeof(PoseEdge);
  for (const CliqueFactor& c : cliques_) {
    bytes += sizeof(CliqueFactor) + c.nodes.capacity() * sizeof(NodeId) +
             c.T_root_node.capacity() * sizeof(Pose2) +
             static_cast<std::size_t>(c.information.size()) * sizeof(double);
  }
  for (const auto& [id, neighbours] : adjacency_) {
    // A std::map / std::set node is roughly three pointers, a colour and the payload.
    // ... and the pair's factor count beside it.
    bytes += 2 * (48 + sizeof(NodeId) + neighbours.size() * (40 + 2 * sizeof(NodeId)));
  }
  return bytes;
}

}  // namespace lifelong::slam
