#include "slam/dijkstra.hpp"

#include <cmath>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

#include <Eigen/LU>

namespace lifelong::slam {
namespace {

struct Link {
  NodeId to;
  Eigen::Matrix3d covariance;  // of the relative pose, in its own error coordinates
};

Eigen::Matrix3d SafeInverse(const Eigen::Matrix3d& information) {
  Eigen::Matrix3d sym = 0.5 * (information + information.transpose());
  sym += 1e-9 * Eigen::Matrix3d::Identity();
  return sym.inverse();
}

// Adjacency with one covariance per directed link. A clique factor contributes a link from
// its root to each member (the block of the inverse information) and between members (sum).
std::map<NodeId, std::vector<Link>> BuildLinks(const PoseGraph& graph) {
  std::map<NodeId, std::vector<Link>> links;
  for (const PoseEdge& e : graph.edges()) {
    const Eigen::Matrix3d c = SafeInverse(e.information);
    links[e.from].push_back({e.to, c});
    links[e.to].push_back({e.from, c});
  }
  for (const CliqueFactor& f : graph.cliques()) {
    const Eigen::MatrixXd sigma =
        (f.information +
         1e-9 * Eigen::MatrixXd::Identity(f.information.rows(), f.information.cols()))
            .inverse();
    const std::size_t k = f.nodes.size() - 1;
    for (std::size_t j = 0; j < k; ++j) {
      const Eigen::Matrix3d c = sigma.block<3, 3>(3 * j, 3 * j);  // block j at row 3j
      links[f.nodes[0]].push_back({f.nodes[j + 1], c});
      links[f.nodes[j + 1]].push_back({f.nodes[0], c});
      for (std::size_t i = 0; i < j; ++i) {
        const Eigen::Matrix3d cij = c + sigma.block<3, 3>(3 * i, 3 * i);
        links[f.nodes[i + 1]].push_back({f.nodes[j + 1], cij});
        links[f.nodes[j + 1]].push_back({f.nodes[i + 1], cij});
      }
    }
  }
  return links;
}

double Distance(const Pose2& a, const Pose2& b) { return std::hypot(b.x - a.x, b.y - a.y); }

}  // namespace

std::map<NodeId, ProjectedNode> ProjectCovariances(const PoseGraph& graph, const Values& values,
                                                   NodeId source, const ProjectionConfig& config) {
  const auto links = BuildLinks(graph);
  std::map<NodeId, ProjectedNode> done;
  using Entry = std::pair<double, NodeId>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  std::map<NodeId, ProjectedNode> best;
  best[source] = ProjectedNode{Eigen::Matrix3d::Zero(), 0.0, 0};
  queue.push({0.0, source});
  const double max_trace = 2.0 * config.max_position_sigma_m * config.max_position_sigma_m;
  while (!queue.empty()) {
    const auto [cost, u] = queue.top();
    queue.pop();
    if (done.count(u)) continue;
    const ProjectedNode node_u = best.at(u);
    done[u] = node_u;
    auto it = links.find(u);
    if (it == links.end()) continue;
    const Pose2& Xu = values.at(u);
    for (const Link& link : it->second) {
      if (done.count(link.to)) continue;
      const Pose2& Xv = values.at(link.to);
      const Pose2 Z = Between(Xu, Xv);
      const double cu = std::cos(Xu.theta), su = std::sin(Xu.theta);
      Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
      A(0, 2) = -su * Z.x - cu * Z.y;
      A(1, 2) = cu * Z.x - su * Z.y;
      const double cw = std::cos(Xu.theta + Z.theta), sw = std::sin(Xu.theta + Z.theta);
      Eigen::Matrix3d B = Eigen::Matrix3d::Identity();  // error frame = relative frame
      B.block<2, 2>(0, 0) << cw, -sw, sw, cw;
      ProjectedNode next;
      next.covariance = A * node_u.covariance * A.transpose() + B * link.covariance * B.transpose();
      next.path_length_m = node_u.path_length_m + Distance(Xu, Xv);
      next.hops = node_u.hops + 1;
      const double next_cost = next.covariance(0, 0) + next.covariance(1, 1);
      if (next_cost > max_trace || next.path_length_m > config.max_path_length_m) continue;
      auto found = best.find(link.to);
      if (found == best.end() ||
          next_cost < found->second.covariance(0, 0) + found->second.covariance(1, 1)) {
        best[link.to] = next;
        queue.push({next_cost, link.to});
      }
    }
  }
  return done;
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
