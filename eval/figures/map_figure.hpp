// Map and graph figures on a canvas of chosen frame, bounds and scale, so that every map of
// a run can be drawn at one scale and orientation (the seed's Figs. 6.6-6.9 put the modes
// side by side). The grid is resampled into the figure frame (nearest cell at each pixel
// centre), then the trajectories are drawn thin, then the graph's edges (coloured by kind,
// render/palette.hpp) and nodes over them, so a sparse graph is never hidden by a path, and
// last the loop closures, thick, so that the short edges of a revisit are not hidden by
// the nodes and edges around them.
#pragma once

#include "eval/figures/draw.hpp"
#include "sensor/pose2.hpp"
#include "types/occupancy_grid.hpp"

namespace lifelong::eval {

/// The image's window onto the figure frame: pixel (u, v), v down from the top, covers
/// [x0_m + u * m_per_px, ...) x [y0_m + (height_px - 1 - v) * m_per_px, ...).
struct Canvas {
  double x0_m = 0.0;       ///< m, figure-frame x of the image's left edge
  double y0_m = 0.0;       ///< m, figure-frame y of the image's bottom edge
  double m_per_px = 0.05;  ///< m per pixel
  int width_px = 0;
  int height_px = 0;
};

/// The canvas covering [x0, x1] x [y0, y1] (figure frame, m), rounded out to whole pixels.
Canvas CanvasCovering(double x0_m, double y0_m, double x1_m, double y1_m, double m_per_px);

/// The canvas covering every cell of `grid` (placed by identity) at m_per_px.
Canvas CanvasOfGrid(const OccupancyGrid& grid, double m_per_px);

/// The canvas covering the known cells of `grid` placed in the figure frame by
/// T_frame_grid, plus margin_m on every side; the whole grid when no cell is known.
Canvas CanvasOfKnownCells(const OccupancyGrid& grid, const Pose2& T_frame_grid, double margin_m,
                          double m_per_px);

struct FigureLayers {
  const OccupancyGrid* grid = nullptr;          ///< nullptr: a white background
  Pose2 T_frame_grid;                           ///< where the grid lies in the figure frame
  std::vector<TrajectoryOverlay> trajectories;  ///< figure frame; 1 px, under the graph
  GraphOverlay graph;                           ///< figure frame
  double node_radius_px = 1.5;                  ///< px
  int loop_edge_width_px = 2;                   ///< px; loop closures go over everything
  bool scale_bar = true;                        ///< a 1/2/5 x 10^k m bar in the lower-left corner
};

/// Draws the layers on the canvas: cells (unknown grey 205, free white, occupied black,
/// grey level 255 * (1 - min(2p, 1))), trajectories, edges, nodes, loop closures, scale bar.
Image RenderFigure(const Canvas& canvas, const FigureLayers& layers);

/// The overlay moved by T (e.g. T_truth_est: from the mapper's frame into the truth's).
GraphOverlay Transformed(const Pose2& T, const GraphOverlay& graph);

/// The poses moved by T.
std::vector<Pose2> Transformed(const Pose2& T, const std::vector<Pose2>& poses);

}  // namespace lifelong::eval
