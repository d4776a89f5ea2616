#include "eval/figures/draw.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include <png.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/figures/map_figure.hpp"
#include "eval/metrics/map_quality.hpp"
#include "io/atomic_file.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

/// The drawn window of the grid: cells [col0, col0 + cols) x [row0, row0 + rows).
struct View {
  int col0 = 0, row0 = 0, cols = 0, rows = 0;
};

View MakeView(const OccupancyGrid& g, const DrawConfig& c) {
  View v{0, 0, g.width, g.height};
  if (!c.crop_to_known) return v;
  int c0 = g.width, r0 = g.height, c1 = -1, r1 = -1;
  for (int r = 0; r < g.height; ++r)
    for (int col = 0; col < g.width; ++col)
      if (g.At(col, r) >= 0.0f)
        c0 = std::min(c0, col), c1 = std::max(c1, col), r0 = std::min(r0, r), r1 = std::max(r1, r);
  if (c1 < 0) return v;  // nothing known: keep the whole grid
  const int m = static_cast<int>(std::ceil(c.margin_m / g.resolution_m - 1e-9));
  v.col0 = std::max(c0 - m, 0), v.row0 = std::max(r0 - m, 0);
  v.cols = std::min(c1 + m + 1, g.width) - v.col0;
  v.rows = std::min(r1 + m + 1, g.height) - v.row0;
  return v;
}

}  // namespace

GraphOverlay MakeGraphOverlay(const slam::PoseGraph& graph, const slam::Values& values) {
  GraphOverlay o;
  for (const auto& [id, pose] : values) o.nodes.push_back(pose);
  auto add = [&](slam::NodeId a, slam::NodeId b, EdgeKind kind) {
    const auto ia = values.find(a), ib = values.find(b);
    if (ia == values.end() || ib == values.end()) return;
    o.edges.push_back({{ia->second.x, ia->second.y, ib->second.x, ib->second.y}, kind});
  };
  for (const slam::PoseEdge& e : graph.edges()) add(e.from, e.to, e.kind);
  for (const slam::CliqueFactor& c : graph.cliques())
    for (std::size_t i = 1; i < c.nodes.size(); ++i)
      add(c.nodes[0], c.nodes[i], EdgeKind::kMarginal);
  return o;
}

Image RenderMap(const OccupancyGrid& grid, const GraphOverlay& graph,
                const std::vector<TrajectoryOverlay>& trajectories, const DrawConfig& config) {
  if (grid.width <= 0 || grid.height <= 0) return {};
  const View v = MakeView(grid, config);
  const int scale = std::max(config.pixels_per_cell, 1);
  Canvas canvas;
  canvas.x0_m = grid.origin_x_m + v.col0 * grid.resolution_m;
  canvas.y0_m = grid.origin_y_m + v.row0 * grid.resolution_m;
  canvas.m_per_px = grid.resolution_m / scale;
  canvas.width_px = v.cols * scale;
  canvas.height_px = v.rows * scale;
  FigureLayers layers;
  layers.grid = &grid;
  layers.trajectories = trajectories;
  layers.graph = graph;
  layers.scale_bar = config.scale_bar;
  return RenderFigure(canvas, layers);
}

void WritePng(const std::string& path, const Image& image) {
  // libpng's simplified API (no setjmp), compressing once into a buffer of the bound
  // PNG_IMAGE_PNG_SIZE_MAX (left uninitialized: only the bytes written are touched).
  const auto fail = [&](const std::string& why) {
    return InputError(path, 0, "", "cannot encode the image as PNG: " + why);
  };
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) {
    throw fail("no pixels, or not width x height x 3 bytes");
  }
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  // Speed before size: the adaptive filters and full compression took ~8 % of an Intel run.
  png.flags = PNG_IMAGE_FLAG_FAST;
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(png);
  const std::unique_ptr<char[]> bytes(new char[size]);
  const auto stride = static_cast<png_int_32>(image.width) * 3;
  if (!png_image_write_to_memory(&png, bytes.get(), &size, 0, image.rgb.data(), stride, nullptr)) {
    throw fail(png.message);
  }
  io::WriteFileAtomically(path, std::string_view(bytes.get(), size));
}

void WriteMapPng(const std::string& path, const OccupancyGrid& grid, const GraphOverlay& graph,
                 const std::vector<TrajectoryOverlay>& trajectories, const DrawConfig& config) {
  WritePng(path, RenderMap(grid, graph, trajectories, config));
}

void WriteWorldPng(const std::string& path, const std::vector<Segment>& walls,
                   const std::vector<TrajectoryOverlay>& trajectories, const DrawConfig& config) {
  const OccupancyGrid grid = RasterizeWalls(walls, config.world_resolution_m, config.margin_m);
  DrawConfig c = config;
  c.crop_to_known = false;  // every cell is known; the raster already has the margin
  WriteMapPng(path, grid, GraphOverlay{}, trajectories, c);
}

}  // namespace lifelong::eval
