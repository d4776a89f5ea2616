// Maps as images (OpenCV): an OccupancyGrid as a PNG with y up (grid row 0 is the image's
// bottom row), unknown grey, free white, occupied black (grey level 255 * (1 - p)), with
// optional overlays drawn in world coordinates: the pose graph (nodes as dots, edges
// coloured by kind) and trajectories (true green, odometry red, estimate blue; drawn thin and
// under the graph). eval/figures/map_figure.hpp draws the same in any frame and scale. Images are
// written atomically (io/atomic_file.hpp), so a PNG that exists is whole.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"
#include "types/edge_kind.hpp"
#include "types/image.hpp"
#include "types/occupancy_grid.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

enum class TrajectoryKind : std::uint8_t { kTrue, kOdometry, kEstimate };

struct TrajectoryOverlay {
  TrajectoryKind kind = TrajectoryKind::kEstimate;
  std::vector<Pose2> poses;  ///< world frame of the map
};

struct GraphOverlay {
  std::vector<Pose2> nodes;
  std::vector<GraphEdge> edges;  ///< end points in the world frame, m
};

/// Nodes and edges of a graph at the given estimate; a clique factor is drawn as marginal
/// edges from its root to each other node. Edges with a node missing from `values` are
/// skipped.
GraphOverlay MakeGraphOverlay(const slam::PoseGraph& graph, const slam::Values& values);

struct DrawConfig {
  bool crop_to_known = true;         ///< crop to the bounding box of known cells ...
  double margin_m = 1.0;             ///< ... plus this margin, m
  int pixels_per_cell = 1;           ///< integer upscaling of the grid
  bool scale_bar = true;             ///< a 1/2/5 x 10^k m bar in the lower-left corner
  double world_resolution_m = 0.05;  ///< m per cell when drawing true walls (WriteWorldPng)
};

/// Renders the grid with overlays; the caller may inspect pixels (tests) or write it.
Image RenderMap(const OccupancyGrid& grid, const GraphOverlay& graph,
                const std::vector<TrajectoryOverlay>& trajectories, const DrawConfig& config = {});

/// Writes an image as PNG (atomically). Throws InputError (a std::runtime_error) naming the
/// path.
void WritePng(const std::string& path, const Image& image);

/// RenderMap + WritePng.
void WriteMapPng(const std::string& path, const OccupancyGrid& grid, const GraphOverlay& graph,
                 const std::vector<TrajectoryOverlay>& trajectories, const DrawConfig& config = {});

/// The true world (walls black on white, rasterized at config.world_resolution_m) with
/// trajectories over it, e.g. the true and odometry paths written by `simulate`.
void WriteWorldPng(const std::string& path, const std::vector<Segment>& walls,
                   const std::vector<TrajectoryOverlay>& trajectories,
                   const DrawConfig& config = {});

}  // namespace lifelong::eval
