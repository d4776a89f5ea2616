#include "eval/figures/map_figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "render/palette.hpp"

namespace lifelong::eval {
namespace {

constexpr int kShift = 4;  // sub-pixel bits for cv drawing
constexpr double kSub = 16.0;

// The figure is drawn straight into the RGB bytes of a lifelong::Image: OpenCV's drawing
// treats the channels alike, so a colour is given in the image's (RGB) order.
cv::Scalar Colour(const render::Rgb& c) {
  return {static_cast<double>(c.r), static_cast<double>(c.g), static_cast<double>(c.b)};
}

cv::Scalar TrajectoryColour(TrajectoryKind k) {
  switch (k) {
    case TrajectoryKind::kTrue:
      return Colour(render::kTrueTrajectory);
    case TrajectoryKind::kOdometry:
      return Colour(render::kOdometryTrajectory);
    default:
      return Colour(render::kEstimateTrajectory);
  }
}

/// Figure-frame metres to sub-pixel image coordinates (row 0 at the top). OpenCV puts
/// pixel i's centre at i, the cells are sampled at i + 0.5: hence the half pixel.
cv::Point Px(const Canvas& c, double x, double y) {
  const double u = (x - c.x0_m) / c.m_per_px - 0.5;
  const double v = c.height_px - (y - c.y0_m) / c.m_per_px - 0.5;
  return {static_cast<int>(std::lround(u * kSub)), static_cast<int>(std::lround(v * kSub))};
}

/// Reflection probabilities of walls are often well below 1 (grazing beams pass through
/// them), so the grey ramp saturates at p = 0.5: black = at least as often hit as passed.
std::uint8_t Grey(float p) {
  if (p < 0.0f) return 205;
  const double level = 255.0 * (1.0 - std::min(2.0 * static_cast<double>(p), 1.0));
  return static_cast<std::uint8_t>(std::lround(level));
}

/// Each pixel centre mapped into the grid, nearest cell; outside the grid is unknown.
void DrawCells(const Canvas& c, const OccupancyGrid& g, const Pose2& T_frame_grid, cv::Mat& img) {
  const Pose2 T_grid_frame = T_frame_grid.Inverse();
  const double cs = std::cos(T_grid_frame.theta), sn = std::sin(T_grid_frame.theta);
  for (int v = 0; v < c.height_px; ++v) {
    const double yf = c.y0_m + (c.height_px - v - 0.5) * c.m_per_px;
    auto* row_px = img.ptr<cv::Vec3b>(v);
    for (int u = 0; u < c.width_px; ++u) {
      const double xf = c.x0_m + (u + 0.5) * c.m_per_px;
      const double gx = T_grid_frame.x + cs * xf - sn * yf;
      const double gy = T_grid_frame.y + sn * xf + cs * yf;
      const double col = std::floor((gx - g.origin_x_m) / g.resolution_m);
      const double row = std::floor((gy - g.origin_y_m) / g.resolution_m);
      float p = OccupancyGrid::kUnknown;
      if (col >= 0 && row >= 0 && col < g.width && row < g.height) {
        p = g.At(static_cast<int>(col), static_cast<int>(row));
      }
      const std::uint8_t grey = Grey(p);
      row_px[u] = cv::Vec3b(grey, grey, grey);
    }
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
  // A white box behind bar and label keeps them readable over walls and edges.
  cv::rectangle(img, cv::Point(4, img.rows - 32), cv::Point(16 + px, img.rows - 4),
                cv::Scalar(255, 255, 255), cv::FILLED);
  cv::line(img, a, b, cv::Scalar(0, 0, 0), 3);
  char text[32];
  std::snprintf(text, sizeof(text), "%g m", len);
  cv::putText(img, text, a + cv::Point(0, -8), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0),
              1, cv::LINE_AA);
}

}  // namespace

Canvas CanvasCovering(double x0_m, double y0_m, double x1_m, double y1_m, double m_per_px) {
  Canvas c;
  c.x0_m = x0_m, c.y0_m = y0_m, c.m_per_px = m_per_px;
  // The epsilon keeps a box of exactly n pixels at n (a grid's extent at its resolution).
  c.width_px = std::max(1, static_cast<int>(std::ceil((x1_m - x0_m) / m_per_px - 1e-6)));
  c.height_px = std::max(1, static_cast<int>(std::ceil((y1_m - y0_m) / m_per_px - 1e-6)));
  return c;
}

Canvas CanvasOfGrid(const OccupancyGrid& g, double m_per_px) {
  return CanvasCovering(g.origin_x_m, g.origin_y_m, g.origin_x_m + g.width * g.resolution_m,
                        g.origin_y_m + g.height * g.resolution_m, m_per_px);
}

Canvas CanvasOfKnownCells(const OccupancyGrid& g, const Pose2& T_frame_grid, double margin_m,
                          double m_per_px) {
  int c0 = g.width, r0 = g.height, c1 = -1, r1 = -1;
  for (int r = 0; r < g.height; ++r) {
    for (int col = 0; col < g.width; ++col) {
      if (g.At(col, r) < 0.0f) continue;
      c0 = std::min(c0, col), c1 = std::max(c1, col), r0 = std::min(r0, r), r1 = std::max(r1, r);
    }
  }
  if (c1 < 0) c0 = 0, r0 = 0, c1 = g.width - 1, r1 = g.height - 1;
  double x0 = std::numeric_limits<double>::max(), y0 = x0;
  double x1 = std::numeric_limits<double>::lowest(), y1 = x1;
  for (int corner = 0; corner < 4; ++corner) {  // the known box's corners in the frame
    const double gx = g.origin_x_m + (corner & 1 ? c1 + 1 : c0) * g.resolution_m;
    const double gy = g.origin_y_m + (corner & 2 ? r1 + 1 : r0) * g.resolution_m;
    double x = 0.0, y = 0.0;
    T_frame_grid.Apply(gx, gy, &x, &y);
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  return CanvasCovering(x0 - margin_m, y0 - margin_m, x1 + margin_m, y1 + margin_m, m_per_px);
}

Image RenderFigure(const Canvas& c, const FigureLayers& layers) {
  Image out;
  if (c.width_px <= 0 || c.height_px <= 0) return out;
  out.width = c.width_px, out.height = c.height_px;
  out.rgb.assign(static_cast<std::size_t>(c.width_px) * c.height_px * 3, 255);
  cv::Mat img(c.height_px, c.width_px, CV_8UC3, out.rgb.data());  // a view: no copy
  if (layers.grid && layers.grid->width > 0 && layers.grid->height > 0) {
    DrawCells(c, *layers.grid, layers.T_frame_grid, img);
  }
  for (const TrajectoryOverlay& t : layers.trajectories) {
    for (std::size_t i = 1; i < t.poses.size(); ++i) {
      cv::line(img, Px(c, t.poses[i - 1].x, t.poses[i - 1].y), Px(c, t.poses[i].x, t.poses[i].y),
               TrajectoryColour(t.kind), 1, cv::LINE_AA, kShift);
    }
  }
  const auto draw_edges = [&](bool loops, int width_px) {
    for (const GraphEdge& e : layers.graph.edges) {
      if ((e.kind == EdgeKind::kLoop) != loops) continue;
      const Segment& s = e.segment;
      cv::line(img, Px(c, s.x0, s.y0), Px(c, s.x1, s.y1), Colour(render::EdgeColour(e.kind)),
               width_px, cv::LINE_AA, kShift);
    }
  };
  draw_edges(false, 1);
  const int radius = static_cast<int>(std::lround(layers.node_radius_px * kSub));
  for (const Pose2& n : layers.graph.nodes) {
    cv::circle(img, Px(c, n.x, n.y), radius, Colour(render::kGraphNode), cv::FILLED, cv::LINE_AA,
               kShift);
  }
  // Loop closures join nodes that lie close together, on the path: drawn under it they
  // vanish. Last and thick, they show.
  draw_edges(true, std::max(layers.loop_edge_width_px, 1));
  if (layers.scale_bar) DrawScaleBar(img, c.m_per_px);
  return out;
}

GraphOverlay Transformed(const Pose2& T, const GraphOverlay& graph) {
  GraphOverlay out;
  out.nodes = Transformed(T, graph.nodes);
  out.edges = graph.edges;
  for (GraphEdge& e : out.edges) {
    Segment& s = e.segment;
    T.Apply(s.x0, s.y0, &s.x0, &s.y0);
    T.Apply(s.x1, s.y1, &s.x1, &s.y1);
  }
  return out;
}

std::vector<Pose2> Transformed(const Pose2& T, const std::vector<Pose2>& poses) {
  std::vector<Pose2> out;
  out.reserve(poses.size());
  for (const Pose2& p : poses) out.push_back(T * p);
  return out;
}

}  // namespace lifelong::eval
