// The scene helpers of eval/figures/video.hpp: plain data from the mapper's state.
#include "eval/figures/video.hpp"

#include <cmath>
#include <cstdio>

#include "eval/figures/draw.hpp"

namespace lifelong::eval {

render::Panel MakePanel(const std::string& title, const OccupancyGrid& map,
                        const slam::PoseGraph& graph, const slam::Values& values,
                        const Pose2& robot_estimate, int observation) {
  render::Panel panel;
  panel.title = title;
  panel.map = map;
  GraphOverlay overlay = MakeGraphOverlay(graph, values);
  panel.nodes = std::move(overlay.nodes);
  panel.edges = std::move(overlay.edges);
  panel.robot_estimate = robot_estimate;
  panel.observation = observation;
  panel.node_count = graph.NumNodes();
  panel.edge_count = graph.NumEdgesForGamma();
  return panel;
}

render::Scene MakeScene(const std::vector<Segment>& walls, const Pose2& T_world_robot,
                        const LaserScan& scan, std::vector<render::Panel> panels) {
  render::Scene scene;
  scene.walls = walls;
  scene.robot_true = T_world_robot;
  const Pose2 T_world_laser = T_world_robot * scan.T_robot_laser;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!scan.IsReturn(i)) continue;
    const double r = scan.ranges_m[i], a = scan.Bearing(i);
    double x = 0.0, y = 0.0;
    T_world_laser.Apply(r * std::cos(a), r * std::sin(a), &x, &y);
    scene.rays.push_back({T_world_laser.x, T_world_laser.y, x, y});
  }
  char caption[48];
  std::snprintf(caption, sizeof(caption), "t %.1f s", scan.stamp_s);
  scene.world_caption = caption;
  scene.panels = std::move(panels);
  return scene;
}

}  // namespace lifelong::eval
