#include "eval/draw.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/map_quality.hpp"
#include "io/atomic_file.hpp"
#include "render/palette.hpp"

namespace lifelong::eval {
namespace {

constexpr int kShift = 4;  // sub-pixel bits for cv drawing
constexpr double kSub = 16.0;

/// The drawn window of the grid: cells [col0, col0 + cols) x [row0, row0 + rows).
struct View {
  const OccupancyGrid* grid = nullptr;
  int col0 = 0, row0 = 0, cols = 0, rows = 0, scale = 1;
  cv::Point Px(double x, double y) const {
    const double c = (x - grid->origin_x_m) / grid->resolution_m - col0;
    const double r = (y - grid->origin_y_m) / grid->resolution_m - row0;
    return {static_cast<int>(std::lround(c * scale * kSub)),
            static_cast<int>(std::lround((rows - r) * scale * kSub))};
  }
};

View MakeView(const OccupancyGrid& g, const DrawConfig& c) {
  View v{&g, 0, 0, g.width, g.height, std::max(c.pixels_per_cell, 1)};
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

cv::Mat DrawCells(const View& v) {
  cv::Mat small(v.rows, v.cols, CV_8UC3);
  for (int r = 0; r < v.rows; ++r) {
    for (int c = 0; c < v.cols; ++c) {
      const float p = v.grid->At(v.col0 + c, v.row0 + r);
      // Reflection probabilities of walls are often well below 1 (grazing beams pass
      // through them), so the grey ramp saturates at p = 0.5: black = at least as often hit
      // as passed.
      const int grey = p < 0.0f ? 205
                                : static_cast<int>(std::lround(
                                      255.0 * (1.0 - std::min(2.0 * static_cast<double>(p), 1.0))));
      const auto u = static_cast<uchar>(grey);
      small.at<cv::Vec3b>(v.rows - 1 - r, c) = cv::Vec3b(u, u, u);
    }
  }
  if (v.scale == 1) return small;
  cv::Mat big;
  cv::resize(small, big, cv::Size(), v.scale, v.scale, cv::INTER_NEAREST);
  return big;
}

cv::Scalar EdgeColour(EdgeKind k) {
  const render::Rgb c = render::EdgeColour(k);
  return {static_cast<double>(c.b), static_cast<double>(c.g), static_cast<double>(c.r)};  // BGR
}

cv::Scalar TrajectoryColour(TrajectoryKind k) {
  switch (k) {
    case TrajectoryKind::kTrue:
      return {0, 160, 0};
    case TrajectoryKind::kOdometry:
      return {0, 0, 220};
    default:
      return {220, 0, 0};
  }
}

void DrawScaleBar(cv::Mat& img, double m_per_px) {
  const double target_m = img.cols * m_per_px / 5.0;
  const double base = std::pow(10.0, std::floor(std::log10(std::max(target_m, 1e-3))));
  double len = base;  // the largest of 1, 2, 5 x 10^k not above a fifth of the width
  for (double f : {2.0, 5.0})
    if (base * f <= target_m) len = base * f;
  const int px = static_cast<int>(std::lround(len / m_per_px));
  const cv::Point a(10, img.rows - 10), b(10 + px, img.rows - 10);
  cv::line(img, a, b, cv::Scalar(0, 0, 0), 3);
  char text[32];
  std::snprintf(text, sizeof(text), "%g m", len);
  cv::putText(img, text, a + cv::Point(0, -8), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0),
              1, cv::LINE_AA);
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
  Image out;
  if (grid.width <= 0 || grid.height <= 0) return out;
  const View v = MakeView(grid, config);
  cv::Mat img = DrawCells(v);
  for (const GraphEdge& e : graph.edges) {
    const Segment& s = e.segment;
    cv::line(img, v.Px(s.x0, s.y0), v.Px(s.x1, s.y1), EdgeColour(e.kind), 1, cv::LINE_AA, kShift);
  }
  for (const Pose2& n : graph.nodes)
    cv::circle(img, v.Px(n.x, n.y), static_cast<int>(1.5 * kSub), cv::Scalar(90, 40, 0), cv::FILLED,
               cv::LINE_AA, kShift);
  for (const TrajectoryOverlay& t : trajectories)
    for (std::size_t i = 1; i < t.poses.size(); ++i)
      cv::line(img, v.Px(t.poses[i - 1].x, t.poses[i - 1].y), v.Px(t.poses[i].x, t.poses[i].y),
               TrajectoryColour(t.kind), 1, cv::LINE_AA, kShift);
  if (config.scale_bar) DrawScaleBar(img, grid.resolution_m / v.scale);
  cv::cvtColor(img, img, cv::COLOR_BGR2RGB);
  out.width = img.cols, out.height = img.rows;
  out.rgb.assign(img.data, img.data + img.total() * img.elemSize());
  return out;
}

void WritePng(const std::string& path, const Image& image) {
  const cv::Mat rgb(image.height, image.width, CV_8UC3,
                    const_cast<std::uint8_t*>(image.rgb.data()));
  cv::Mat bgr;
  if (!rgb.empty()) cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  io::WriteThroughTempFile(path, [&](const std::string& tmp) {  // ".png" kept for imwrite
    try {
      return !bgr.empty() && cv::imwrite(tmp, bgr);
    } catch (const cv::Exception&) {
      return false;
    }
  });
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
