// The mapper's side of the front end (DESIGN.md data flow, step 2): a new observation becomes
// a graph node, tied to the last one by the sequential matcher's edge
// (slam/matching/sequential_matcher.hpp), and its scan goes to the map and the scan store.
#include <cstddef>
#include <utility>
#include <vector>

#include "slam/graph/se2.hpp"
#include "slam/mapping/mapper_state.hpp"
#include "slam/matching/scan_matcher.hpp"
#include "slam/matching/sequential_matcher.hpp"

namespace lifelong::slam {

void Mapper::State::AddSequentialNode(const Observation& obs, StepStats* stats) {
  const IncrementalConfig& inc = config.incremental;
  NodeData data;
  data.scan = obs.scan;
  data.points = ScanToPoints(obs.scan, inc.point_spacing_m);
  data.T_odom_robot = obs.T_odom_robot;
  data.scan_index = static_cast<int>(scans.size());
  const NodeId id = next_id++;
  graph.AddNode(id);
  if (!have_last) {
    values[id] = Pose2();
  } else {
    const Pose2 delta = Between(nodes.at(last_node).T_odom_robot, obs.T_odom_robot);
    data.travelled_m = nodes.at(last_node).travelled_m + Norm(delta);
    Pose2 X_new;
    graph.AddEdge(SequentialEdge(id, delta, obs.odometry_lost, data.points, &X_new, stats));
    values[id] = X_new;
  }
  data.T_world_map = values.at(id);
  keeper.Add(id, data.scan, data.T_world_map);
  nodes.emplace(id, std::move(data));
  recent.push_back(id);

  if (have_last) scans.AnchorPending(last_node, id, obs.T_odom_robot);
  const std::size_t scan = scans.AddNodeScan(obs.stamp_s, id, obs.T_odom_robot);
  const NodeData& node = nodes.at(id);
  sequential.Remember(id, scan, node.scan, node.points);
  last_node = id;
  have_last = true;
}

PoseEdge Mapper::State::SequentialEdge(NodeId id, const Pose2& delta, bool odometry_lost,
                                       const std::vector<Eigen::Vector2d>& points, Pose2* X_new,
                                       StepStats* stats) {
  const Pose2& X_last = values.at(last_node);
  const SequentialMatch m = sequential.Match(
      [this](NodeId node, std::size_t scan) {  // a surviving node's own pose, exactly
        const auto it = values.find(node);
        return it != values.end() ? it->second : scans.Pose(scan, values);
      },
      X_last, delta, points, odometry_lost);
  stats->local_map_from_scan = m.local_map_from_scan;
  stats->odometry_lost = m.lost;
  stats->incremental_match_ok = m.matched;
  stats->incremental_match_degenerate = m.degenerate;
  stats->incremental_match_weak = m.weak;
  stats->incremental_match_recovered = m.recovered;
  *X_new = m.X_new;
  PoseEdge edge;
  edge.from = last_node;
  edge.to = id;
  edge.kind = EdgeKind::kOdometry;
  edge.information = m.information;
  edge.T_from_to = Between(X_last, *X_new);
  return edge;
}

}  // namespace lifelong::slam
