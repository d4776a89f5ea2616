#include "slam/graph/dijkstra.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "slam/graph/se2.hpp"

namespace lifelong::slam {
namespace {

struct Link {
  int to;                      // dense index of the other node
  Eigen::Matrix3d covariance;  // of the relative pose, in its own error coordinates
};

Eigen::Matrix3d SafeInverse(const Eigen::Matrix3d& information) {
  Eigen::Matrix3d sym = 0.5 * (information + information.transpose());
  sym += 1e-9 * Eigen::Matrix3d::Identity();
  return sym.inverse();
}

// Dense node indexing (ascending ids, the order of Values) and one covariance per directed
// link, from each edge and from the clique factors (grouped by root, below).
struct DenseGraph {
  std::vector<NodeId> ids;
  std::vector<const Pose2*> poses;
  std::vector<std::vector<Link>> links;
  int IndexOf(NodeId id) const {
    return static_cast<int>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
  }
};

/// The clique factors rooted at one node, before they become links.
struct RootGroup {
  std::vector<NodeId> members;  // nodes other than the root, ascending
  std::vector<const CliqueFactor*> factors;
};

/// The covariance of a group's root-relative errors y from their information. A group may be
/// singular alone (GLC conditionals, each rank 3, whose marginal lies in another group): its
/// uninformative directions come out at ~1e9 m^2, which the projection cannot pass, and the
/// informative ones exact, so a link along them (between two members) stays usable.
Eigen::MatrixXd GroupCovariance(const Eigen::MatrixXd& information) {
  const Eigen::MatrixXd sym = 0.5 * (information + information.transpose());
  const Eigen::LLT<Eigen::MatrixXd> llt(sym);
  if (llt.info() == Eigen::Success && llt.rcond() > 1e-10) {
    return llt.solve(Eigen::MatrixXd::Identity(sym.rows(), sym.cols()));
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(sym);
  const Eigen::VectorXd& d = eig.eigenvalues();
  const double floor = 1e-12 * std::max(d.maxCoeff(), 0.0);
  Eigen::VectorXd inv(d.size());
  for (Eigen::Index k = 0; k < d.size(); ++k) inv(k) = 1.0 / (std::max(d(k), floor) + 1e-9);
  return eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

/// Links from the root to each member and between members, from the group's factors and the
/// root's edges to members. y_j = t2v(Z_j^-1 X_r^-1 X_j) is the error of the relative pose
/// r -> j in j's frame, so the link r -> j has the block Sigma_jj, and j -> r, whose error
/// is -Ad(Z_j) y_j in r's frame, Ad(Z_j) Sigma_jj Ad(Z_j)^T; the error of i -> j is
/// d_ij = y_j - Ad(Z_ij^-1) y_i (Z_ij = X_i^-1 X_j), whose covariance takes the pair's
/// correlation from the group's joint covariance.
void AddCliqueLinks(const PoseGraph& graph, NodeId root, RootGroup* group, DenseGraph* g,
                    CliqueGroupCache* cache) {
  std::vector<NodeId>& members = group->members;
  std::sort(members.begin(), members.end());
  members.erase(std::unique(members.begin(), members.end()), members.end());
  const auto at = [&](NodeId id) {
    return 3 * static_cast<Eigen::Index>(std::lower_bound(members.begin(), members.end(), id) -
                                         members.begin());
  };
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(members.size());
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);
  for (const CliqueFactor* f : group->factors) {
    for (std::size_t i = 1; i < f->nodes.size(); ++i) {
      for (std::size_t j = 1; j < f->nodes.size(); ++j) {
        information.block<3, 3>(at(f->nodes[i]), at(f->nodes[j])) += f->information.block<3, 3>(
            3 * static_cast<Eigen::Index>(i - 1), 3 * static_cast<Eigen::Index>(j - 1));
      }
    }
  }
  // Edges from the root to a member inform that member's y directly (GLC's tree marginal).
  for (const PoseEdge& e : graph.edges()) {
    if (e.from == root && std::binary_search(members.begin(), members.end(), e.to)) {
      information.block<3, 3>(at(e.to), at(e.to)) += e.information;
    }
  }
  Eigen::MatrixXd fresh;  // without a cache
  const Eigen::MatrixXd& sigma = cache ? cache->Covariance(root, information, GroupCovariance)
                                       : (fresh = GroupCovariance(information));
  const auto block = [&](std::size_t i, std::size_t j) -> Eigen::Matrix3d {
    return sigma.block<3, 3>(3 * static_cast<Eigen::Index>(i), 3 * static_cast<Eigen::Index>(j));
  };
  const auto link = [&](int from, int to, const Eigen::Matrix3d& c) {
    g->links[static_cast<std::size_t>(from)].push_back({to, c});
  };
  const int r = g->IndexOf(root);
  for (std::size_t j = 0; j < members.size(); ++j) {
    const int m = g->IndexOf(members[j]);
    const Eigen::Matrix3d back = Adjoint(
        Between(*g->poses[static_cast<std::size_t>(r)], *g->poses[static_cast<std::size_t>(m)]));
    link(r, m, block(j, j));
    link(m, r, back * block(j, j) * back.transpose());
    for (std::size_t i = 0; i < j; ++i) {
      const int mi = g->IndexOf(members[i]);
      const Pose2 Z_ij =
          Between(*g->poses[static_cast<std::size_t>(mi)], *g->poses[static_cast<std::size_t>(m)]);
      const Eigen::Matrix3d a = Adjoint(Z_ij.Inverse()), b = Adjoint(Z_ij);
      link(mi, m,
           block(j, j) - block(j, i) * a.transpose() - a * block(i, j) +
               a * block(i, i) * a.transpose());
      link(m, mi,
           block(i, i) - block(i, j) * b.transpose() - b * block(j, i) +
               b * block(j, j) * b.transpose());
    }
  }
}

DenseGraph BuildDense(const PoseGraph& graph, const Values& values, CliqueGroupCache* cache) {
  DenseGraph g;
  g.ids = graph.NodeIds();
  g.poses.reserve(g.ids.size());
  for (NodeId id : g.ids) g.poses.push_back(&values.at(id));
  g.links.resize(g.ids.size());
  for (const PoseEdge& e : graph.edges()) {
    const Eigen::Matrix3d c = SafeInverse(e.information);
    const int a = g.IndexOf(e.from), b = g.IndexOf(e.to);
    g.links[static_cast<std::size_t>(a)].push_back({b, c});
    g.links[static_cast<std::size_t>(b)].push_back({a, c});
  }
  // Clique factors are grouped by root before they become links: their informations are
  // over the same root-relative errors y (pose_graph.hpp), and a sparse GLC (glc.hpp) is a
  // tree of one marginal (an edge from the root) and conditionals whose informations are
  // singular each; only their sum is definite. Inverted one by one, a conditional gives
  // links of ~1e9 m^2 that the projection cannot pass (pruned-glc then found a third of
  // pruned's loop candidates on Intel).
  std::map<NodeId, RootGroup> groups;
  for (const CliqueFactor& f : graph.cliques()) {
    RootGroup& group = groups[f.nodes[0]];
    group.members.insert(group.members.end(), f.nodes.begin() + 1, f.nodes.end());
    group.factors.push_back(&f);
  }
  for (auto& [root, group] : groups) AddCliqueLinks(graph, root, &group, &g, cache);
  if (cache) cache->DropUnused();
  return g;
}

double Distance(const Pose2& a, const Pose2& b) { return std::hypot(b.x - a.x, b.y - a.y); }

}  // namespace

void CliqueGroupCache::DropUnused() {
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (!it->second.used) {
      it = entries_.erase(it);
    } else {
      it->second.used = false;
      ++it;
    }
  }
}

std::map<NodeId, ProjectedNode> ProjectCovariances(const PoseGraph& graph, const Values& values,
                                                   NodeId source, const ProjectionConfig& config,
                                                   CliqueGroupCache* cache) {
  const DenseGraph g = BuildDense(graph, values, cache);
  const std::size_t n = g.ids.size();
  std::vector<ProjectedNode> best(n);
  std::vector<double> cost(n, std::numeric_limits<double>::infinity());
  std::vector<char> done(n, 0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  const int s = g.IndexOf(source);
  best[static_cast<std::size_t>(s)] = ProjectedNode{Eigen::Matrix3d::Zero(), 0.0, 0};
  cost[static_cast<std::size_t>(s)] = 0.0;
  queue.push({0.0, s});
  const double max_trace = 2.0 * config.max_position_sigma_m * config.max_position_sigma_m;
  std::map<NodeId, ProjectedNode> out;
  while (!queue.empty()) {
    const auto [c, u] = queue.top();
    queue.pop();
    const auto uu = static_cast<std::size_t>(u);
    if (done[uu]) continue;
    done[uu] = 1;
    const ProjectedNode& node_u = best[uu];
    out.emplace(g.ids[uu], node_u);
    const Pose2& Xu = *g.poses[uu];
    const double cu = std::cos(Xu.theta), su = std::sin(Xu.theta);
    for (const Link& link : g.links[uu]) {
      const auto v = static_cast<std::size_t>(link.to);
      if (done[v]) continue;
      const Pose2& Xv = *g.poses[v];
      const Pose2 Z = Between(Xu, Xv);
      Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
      A(0, 2) = -su * Z.x - cu * Z.y;
      A(1, 2) = cu * Z.x - su * Z.y;
      const double cw = std::cos(Xv.theta), sw = std::sin(Xv.theta);
      Eigen::Matrix3d B = Eigen::Matrix3d::Identity();  // error frame = relative frame
      B.block<2, 2>(0, 0) << cw, -sw, sw, cw;
      const Eigen::Matrix3d cov =
          A * node_u.covariance * A.transpose() + B * link.covariance * B.transpose();
      const double next_cost = cov(0, 0) + cov(1, 1);
      const double length = node_u.path_length_m + Distance(Xu, Xv);
      if (next_cost > max_trace || length > config.max_path_length_m) continue;
      if (next_cost < cost[v]) {
        cost[v] = next_cost;
        best[v] = ProjectedNode{cov, length, node_u.hops + 1};
        queue.push({next_cost, link.to});
      }
    }
  }
  return out;
}

std::map<NodeId, double> ExpandByPathLength(const PoseGraph& graph, const Values& values,
                                            NodeId source, double max_path_length_m) {
  std::map<NodeId, double> done;
  using Entry = std::pair<double, NodeId>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  queue.push({0.0, source});
  while (!queue.empty()) {
    const auto [length, u] = queue.top();
    queue.pop();
    if (done.count(u)) continue;
    done[u] = length;
    const Pose2& Xu = values.at(u);
    for (NodeId v : graph.Neighbours(u)) {
      if (done.count(v)) continue;
      const double next = length + Distance(Xu, values.at(v));
      if (next <= max_path_length_m) queue.push({next, v});
    }
  }
  return done;
}

bool IsConnected(const PoseGraph& graph) {
  if (graph.NumNodes() == 0) return true;
  std::map<NodeId, bool> seen;
  std::vector<NodeId> stack{graph.NodeIds().front()};
  seen[stack.back()] = true;
  while (!stack.empty()) {
    const NodeId u = stack.back();
    stack.pop_back();
    for (NodeId v : graph.Neighbours(u)) {
      if (!seen[v]) {
        seen[v] = true;
        stack.push_back(v);
      }
    }
  }
  return seen.size() == graph.NumNodes();
}

}  // namespace lifelong::slam
