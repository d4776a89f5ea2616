#include "slam/graph/dijkstra.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <utility>
#include <vector>

#include "slam/graph/se2.hpp"

namespace lifelong::slam {
namespace {

struct Link {
  int to;                      // dense index of the other node
  Eigen::Matrix3d covariance;  // of the relative pose, in its own error coordinates
};

// Dense node indexing (ascending ids, the order of Values) and one covariance per directed
// link, from each edge and from the clique factors (clique_links.hpp).
struct DenseGraph {
  std::vector<NodeId> ids;
  std::vector<const Pose2*> poses;
  std::vector<std::vector<Link>> links;
  int IndexOf(NodeId id) const {
    return static_cast<int>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
  }
};

DenseGraph BuildDense(const PoseGraph& graph, const Values& values, CliqueGroupCache* cache) {
  DenseGraph g;
  g.ids = graph.NodeIds();
  g.poses.reserve(g.ids.size());
  for (NodeId id : g.ids) g.poses.push_back(&values.at(id));
  g.links.resize(g.ids.size());
  for (const PoseEdge& e : graph.edges()) {
    const Eigen::Matrix3d c = RegularizedInverse(e.information);
    const int a = g.IndexOf(e.from), b = g.IndexOf(e.to);
    g.links[static_cast<std::size_t>(a)].push_back({b, c});
    g.links[static_cast<std::size_t>(b)].push_back({a, c});
  }
  for (const CliqueLink& l : CliqueLinks(graph, values, cache)) {
    g.links[static_cast<std::size_t>(g.IndexOf(l.from))].push_back({g.IndexOf(l.to), l.covariance});
  }
  return g;
}

double Distance(const Pose2& a, const Pose2& b) { return std::hypot(b.x - a.x, b.y - a.y); }

}  // namespace

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
