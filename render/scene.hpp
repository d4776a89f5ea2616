// What the renderer draws, as plain data (no simulator, no mapper): the true world with
// the robot and its laser rays, and one panel per mapping mode with its map, pose graph,
// pose estimate and counters. eval builds it (eval/figures/video.hpp); render turns it into pixels.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "sensor/pose2.hpp"
#include "types/edge_kind.hpp"
#include "types/occupancy_grid.hpp"
#include "types/segment.hpp"

namespace lifelong::render {

/// An axis-aligned world rectangle, metres. Empty when min > max.
struct Bounds {
  double min_x = 1.0, min_y = 1.0, max_x = 0.0, max_y = 0.0;

  bool Empty() const { return min_x > max_x || min_y > max_y; }
  void Extend(double x, double y);
  void Extend(const Bounds& other);
};

/// One mapping mode's state at an observation.
struct Panel {
  std::string title;             ///< e.g. the mode's name, "chow-liu"
  OccupancyGrid map;             ///< the mode's current map; may be empty (0 x 0)
  std::vector<Pose2> nodes;      ///< T_world_node at the current estimate
  std::vector<GraphEdge> edges;  ///< graph edges at the current estimate
  Pose2 robot_estimate;          ///< the mode's estimate of the current robot pose
  int observation = 0;           ///< observations processed so far
  std::size_t node_count = 0;    ///< graph nodes (may differ from nodes.size() if thinned)
  std::size_t edge_count = 0;    ///< graph edges as counted for gamma
};

struct Scene {
  std::vector<Segment> walls;  ///< true walls, world frame
  Pose2 robot_true;            ///< T_world_robot, true
  std::vector<Segment> rays;   ///< laser rays, from the laser to each end point (world)
  std::string world_title = "world (ground truth)";
  std::string world_caption;  ///< second line of the world view, e.g. "t 12.3 s"
  std::vector<Panel> panels;  ///< one per mode, drawn side by side after the world view
  /// Region shown in every view; unset: each view is centred on its own content (the
  /// world and each mode's map frame may differ), all at one common scale.
  std::optional<Bounds> view;
};

/// Content of each view: [0] the world (walls, rays, true robot), [1 + i] panel i (map,
/// nodes, estimate). Empty views get a 2 m square around the origin.
std::vector<Bounds> ViewBounds(const Scene& scene);

}  // namespace lifelong::render
