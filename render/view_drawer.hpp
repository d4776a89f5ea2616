// Draws into one view of the frame with fixed-function GL: an orthographic projection of
// the view's world region (render/layout.hpp), then segments, points, triangles and a
// textured grid map. Vertices are sent relative to the view's centre, so large world
// coordinates keep their precision in float. Internal to render.
#pragma once

#include <cstdint>
#include <vector>

#include "render/gl_api.hpp"
#include "render/layout.hpp"
#include "render/palette.hpp"
#include "sensor/pose2.hpp"
#include "types/occupancy_grid.hpp"

namespace lifelong::render {

class ViewDrawer {
 public:
  /// Clears `cell.view` to `background` and sets up its projection.
  ViewDrawer(const GlApi& gl, int frame_height_px, const Cell& cell, Rgb background);

  double metres_per_pixel() const { return m_per_px_; }
  void Lines(const std::vector<Segment>& segments, Rgb colour, float width_px);
  void Points(const std::vector<Pose2>& points, Rgb colour, float size_px);
  /// A filled triangle of length `length_m` pointing along the pose's heading.
  void Robot(const Pose2& pose, double length_m, Rgb colour);
  /// The grid as a texture (texture object `texture`), grey 255 (1 - p), unknown 205;
  /// grids larger than the GL texture limit are reduced by keeping each block's maximum.
  void Map(const OccupancyGrid& grid, unsigned texture);

 private:
  void Draw(unsigned mode, const std::vector<float>& xy, Rgb colour);
  const GlApi& gl_;
  double cx_ = 0.0, cy_ = 0.0, m_per_px_ = 1.0;
};

}  // namespace lifelong::render
