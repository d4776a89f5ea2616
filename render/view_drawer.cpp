#include "render/view_drawer.hpp"

#include <algorithm>
#include <cmath>

namespace lifelong::render {
namespace {

std::uint8_t Grey(float p) {
  if (p < 0.0f) return 205;
  return static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - std::min(p, 1.0f))));
}

// Grey levels of the grid, reduced by `step` cells per texel keeping each block's
// highest occupancy (walls survive); rows bottom first, as GL textures are.
std::vector<std::uint8_t> Texels(const OccupancyGrid& grid, int step, int* w, int* h) {
  *w = (grid.width + step - 1) / step;
  *h = (grid.height + step - 1) / step;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(*w) * static_cast<std::size_t>(*h));
  for (int ty = 0; ty < *h; ++ty) {
    for (int tx = 0; tx < *w; ++tx) {
      float p = OccupancyGrid::kUnknown;
      for (int row = ty * step; row < std::min(grid.height, (ty + 1) * step); ++row)
        for (int col = tx * step; col < std::min(grid.width, (tx + 1) * step); ++col)
          p = std::max(p, grid.At(col, row));
      out[static_cast<std::size_t>(ty) * static_cast<std::size_t>(*w) +
          static_cast<std::size_t>(tx)] = Grey(p);
    }
  }
  return out;
}

}  // namespace

ViewDrawer::ViewDrawer(const GlApi& gl, int frame_height_px, const Cell& cell, Rgb background)
    : gl_(gl) {
  const Rect& v = cell.view;
  const int y_gl = frame_height_px - (v.y + v.height);  // GL windows count rows from below
  gl_.Enable(GL_SCISSOR_TEST);
  gl_.Scissor(v.x, y_gl, v.width, v.height);
  gl_.ClearColor(background.r / 255.0f, background.g / 255.0f, background.b / 255.0f, 1.0f);
  gl_.Clear(GL_COLOR_BUFFER_BIT);
  gl_.Viewport(v.x, y_gl, v.width, v.height);
  const Bounds& s = cell.shown;
  cx_ = 0.5 * (s.min_x + s.max_x);
  cy_ = 0.5 * (s.min_y + s.max_y);
  m_per_px_ = (s.max_x - s.min_x) / v.width;
  gl_.MatrixMode(GL_PROJECTION);
  gl_.LoadIdentity();
  gl_.Ortho(s.min_x - cx_, s.max_x - cx_, s.min_y - cy_, s.max_y - cy_, -1.0, 1.0);
  gl_.MatrixMode(GL_MODELVIEW);
  gl_.LoadIdentity();
}

void ViewDrawer::Draw(unsigned mode, const std::vector<float>& xy, Rgb colour) {
  if (xy.empty()) return;
  gl_.Color3ub(colour.r, colour.g, colour.b);
  gl_.EnableClientState(GL_VERTEX_ARRAY);
  gl_.VertexPointer(2, GL_FLOAT, 0, xy.data());
  gl_.DrawArrays(mode, 0, static_cast<GLsizei>(xy.size() / 2));
  gl_.DisableClientState(GL_VERTEX_ARRAY);
}

void ViewDrawer::Lines(const std::vector<Segment>& segments, Rgb colour, float width_px) {
  std::vector<float> xy;
  xy.reserve(segments.size() * 4);
  for (const Segment& s : segments) {
    xy.insert(xy.end(), {static_cast<float>(s.x0 - cx_), static_cast<float>(s.y0 - cy_),
                         static_cast<float>(s.x1 - cx_), static_cast<float>(s.y1 - cy_)});
  }
  gl_.LineWidth(width_px);
  Draw(GL_LINES, xy, colour);
}

void ViewDrawer::Points(const std::vector<Pose2>& points, Rgb colour, float size_px) {
  std::vector<float> xy;
  xy.reserve(points.size() * 2);
  for (const Pose2& p : points) {
    xy.push_back(static_cast<float>(p.x - cx_));
    xy.push_back(static_cast<float>(p.y - cy_));
  }
  gl_.PointSize(size_px);
  Draw(GL_POINTS, xy, colour);
}

void ViewDrawer::Robot(const Pose2& pose, double length_m, Rgb colour) {
  const double corners[3][2] = {
      {length_m, 0.0}, {-0.5 * length_m, 0.4 * length_m}, {-0.5 * length_m, -0.4 * length_m}};
  std::vector<float> xy;
  for (const auto& c : corners) {
    double x = 0.0, y = 0.0;
    pose.Apply(c[0], c[1], &x, &y);
    xy.push_back(static_cast<float>(x - cx_));
    xy.push_back(static_cast<float>(y - cy_));
  }
  Draw(GL_TRIANGLES, xy, colour);
}

void ViewDrawer::Map(const OccupancyGrid& grid, unsigned texture) {
  if (grid.width <= 0 || grid.height <= 0) return;
  GLint max_size = 1024;
  gl_.GetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  const int step = (std::max(grid.width, grid.height) + max_size - 1) / max_size;
  int w = 0, h = 0;
  const std::vector<std::uint8_t> texels = Texels(grid, step, &w, &h);
  gl_.BindTexture(GL_TEXTURE_2D, texture);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl_.TexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE8, w, h, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE,
                 texels.data());
  const double x0 = grid.origin_x_m - cx_, y0 = grid.origin_y_m - cy_;
  const double x1 = x0 + w * step * grid.resolution_m, y1 = y0 + h * step * grid.resolution_m;
  const std::vector<float> xy = {static_cast<float>(x0), static_cast<float>(y0),
                                 static_cast<float>(x1), static_cast<float>(y0),
                                 static_cast<float>(x1), static_cast<float>(y1),
                                 static_cast<float>(x0), static_cast<float>(y1)};
  const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  gl_.Enable(GL_TEXTURE_2D);
  gl_.EnableClientState(GL_TEXTURE_COORD_ARRAY);
  gl_.TexCoordPointer(2, GL_FLOAT, 0, uv);
  Draw(GL_QUADS, xy, {255, 255, 255});
  gl_.DisableClientState(GL_TEXTURE_COORD_ARRAY);
  gl_.Disable(GL_TEXTURE_2D);
}

}  // namespace lifelong::render
