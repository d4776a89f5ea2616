#include "slam/backend/optimizer_problem.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "slam/graph/se2.hpp"

namespace lifelong::slam::backend {
namespace {

int Rank(const Layout& layout, int a, int b) {
  if (a == kNoBlock || b == kNoBlock) return -1;
  if (a > b) std::swap(a, b);
  const std::vector<int>& rows = layout.rows_of_col[static_cast<std::size_t>(b)];
  if (a == b) return static_cast<int>(rows.size());
  return static_cast<int>(std::lower_bound(rows.begin(), rows.end(), a) - rows.begin());
}

void AddPair(Layout* layout, int node_u, int node_v) {
  int a = layout->block[static_cast<std::size_t>(node_u)];
  int b = layout->block[static_cast<std::size_t>(node_v)];
  if (a == kNoBlock || b == kNoBlock || a == b) return;
  if (a > b) std::swap(a, b);
  layout->rows_of_col[static_cast<std::size_t>(b)].push_back(a);
}

// Dense node indices (ascending ids), anchor and factor-less nodes without columns.
void AssignBlocks(const PoseGraph& graph, Values* values, NodeId anchor, Layout* layout) {
  const std::vector<NodeId> ids = graph.NodeIds();
  layout->poses.resize(ids.size());
  layout->block.assign(ids.size(), kNoBlock);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    auto it = values->find(ids[k]);
    if (it == values->end()) {
      throw std::invalid_argument("Optimize: no value for node " + std::to_string(ids[k]));
    }
    layout->poses[k] = &it->second;
    if (ids[k] != anchor && !graph.Neighbours(ids[k]).empty()) {
      layout->block[k] = layout->num_blocks++;
    }
  }
}

int DenseIndex(const std::vector<NodeId>& ids, NodeId id) {
  return static_cast<int>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
}

}  // namespace

Layout BuildLayout(const PoseGraph& graph, Values* values, NodeId anchor) {
  Layout layout;
  AssignBlocks(graph, values, anchor, &layout);
  const std::vector<NodeId> ids = graph.NodeIds();
  layout.rows_of_col.resize(static_cast<std::size_t>(layout.num_blocks));
  for (const PoseEdge& e : graph.edges()) {
    EdgeSlot slot{&e, DenseIndex(ids, e.from), DenseIndex(ids, e.to), -1, -1, -1};
    AddPair(&layout, slot.i, slot.j);
    layout.edges.push_back(slot);
  }
  for (const CliqueFactor& c : graph.cliques()) {
    CliqueSlot slot{&c, {}, {}};
    for (NodeId n : c.nodes) slot.nodes.push_back(DenseIndex(ids, n));
    for (std::size_t u = 0; u < slot.nodes.size(); ++u) {
      for (std::size_t v = u + 1; v < slot.nodes.size(); ++v) {
        AddPair(&layout, slot.nodes[u], slot.nodes[v]);
      }
    }
    layout.cliques.push_back(std::move(slot));
  }
  for (auto& rows : layout.rows_of_col) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
  const auto& blk = layout.block;
  for (EdgeSlot& s : layout.edges) {
    const int a = blk[static_cast<std::size_t>(s.i)], b = blk[static_cast<std::size_t>(s.j)];
    s.rank_ii = Rank(layout, a, a);
    s.rank_jj = Rank(layout, b, b);
    s.rank_ij = Rank(layout, a, b);
  }
  for (CliqueSlot& s : layout.cliques) {
    for (std::size_t u = 0; u < s.nodes.size(); ++u) {
      for (std::size_t v = u; v < s.nodes.size(); ++v) {
        s.ranks.push_back(Rank(layout, blk[static_cast<std::size_t>(s.nodes[u])],
                               blk[static_cast<std::size_t>(s.nodes[v])]));
      }
    }
  }
  return layout;
}

double Chi2(const Layout& layout, const OptimizerParams& params) {
  double chi2 = 0.0;
  for (const EdgeSlot& s : layout.edges) {
    const Eigen::Vector3d e =
        RelativeError(*layout.poses[static_cast<std::size_t>(s.i)],
                      *layout.poses[static_cast<std::size_t>(s.j)], s.edge->T_from_to);
    chi2 += ApplyKernel(e.dot(s.edge->information * e), s.edge->robust, params).cost;
  }
  for (const CliqueSlot& s : layout.cliques) {
    const Eigen::VectorXd e = CliqueError(*s.clique, [&](std::size_t u) -> const Pose2& {
      return *layout.poses[static_cast<std::size_t>(s.nodes[u])];
    });
    chi2 += e.dot(s.clique->information * e);
  }
  return chi2;
}

void ApplyStep(const Layout& layout, const Eigen::VectorXd& dx) {
  for (std::size_t k = 0; k < layout.poses.size(); ++k) {
    const int a = layout.block[k];
    if (a == kNoBlock) continue;
    Pose2& x = *layout.poses[k];
    x = Pose2(x.x + dx[3 * a], x.y + dx[3 * a + 1], x.theta + dx[3 * a + 2]);
  }
}

std::vector<Pose2> Snapshot(const Layout& layout) {
  std::vector<Pose2> out;
  out.reserve(layout.poses.size());
  for (const Pose2* p : layout.poses) out.push_back(*p);
  return out;
}

void Restore(const Layout& layout, const std::vector<Pose2>& saved) {
  for (std::size_t k = 0; k < saved.size(); ++k) *layout.poses[k] = saved[k];
}

}  // namespace lifelong::slam::backend
