#include "render/layout.hpp"

#include <algorithm>

namespace lifelong::render {
namespace {

// Size of one cell's view for a grid with `cols` columns.
void ViewSize(std::size_t cells, std::size_t cols, const LayoutConfig& c, int* w, int* h) {
  const std::size_t rows = (cells + cols - 1) / cols;
  *w = std::max(1, c.width_px / static_cast<int>(cols) - 2 * c.margin_px);
  *h = std::max(1, c.height_px / static_cast<int>(rows) - c.title_px - 2 * c.margin_px);
}

Bounds FitAspect(const Bounds& world, int w, int h) {
  const double cx = 0.5 * (world.min_x + world.max_x), cy = 0.5 * (world.min_y + world.max_y);
  double half_x = std::max(0.5 * (world.max_x - world.min_x), 0.5);
  double half_y = std::max(0.5 * (world.max_y - world.min_y), 0.5);
  const double aspect = static_cast<double>(w) / static_cast<double>(h);
  if (half_x / half_y < aspect) {
    half_x = half_y * aspect;
  } else {
    half_y = half_x / aspect;
  }
  return {cx - half_x, cy - half_y, cx + half_x, cy + half_y};
}

}  // namespace

std::vector<Cell> ComputeLayout(std::size_t cells, const Bounds& world,
                                const LayoutConfig& config) {
  if (cells == 0) return {};
  const double ww = std::max(world.max_x - world.min_x, 1.0);
  const double wh = std::max(world.max_y - world.min_y, 1.0);
  std::size_t best_cols = 1;
  double best_scale = -1.0;
  for (std::size_t cols = 1; cols <= cells; ++cols) {
    int w = 0, h = 0;
    ViewSize(cells, cols, config, &w, &h);
    const double scale = std::min(w / ww, h / wh);  // pixels per metre
    if (scale > best_scale) best_scale = scale, best_cols = cols;
  }
  const std::size_t rows = (cells + best_cols - 1) / best_cols;
  const int cell_w = config.width_px / static_cast<int>(best_cols);
  const int cell_h = config.height_px / static_cast<int>(rows);
  int view_w = 0, view_h = 0;
  ViewSize(cells, best_cols, config, &view_w, &view_h);
  std::vector<Cell> out(cells);
  for (std::size_t i = 0; i < cells; ++i) {
    const int x = static_cast<int>(i % best_cols) * cell_w;
    const int y = static_cast<int>(i / best_cols) * cell_h;
    out[i].title = {x + config.margin_px, y, cell_w - 2 * config.margin_px, config.title_px};
    out[i].view = {x + config.margin_px, y + config.title_px + config.margin_px, view_w, view_h};
    out[i].shown = FitAspect(world, view_w, view_h);
  }
  return out;
}

std::vector<Cell> ComputeLayout(const std::vector<Bounds>& views, const LayoutConfig& config) {
  double w = 0.0, h = 0.0;
  for (const Bounds& v : views) {
    w = std::max(w, v.max_x - v.min_x);
    h = std::max(h, v.max_y - v.min_y);
  }
  std::vector<Cell> cells = ComputeLayout(views.size(), {0.0, 0.0, w, h}, config);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    Bounds& s = cells[i].shown;
    const double dx = 0.5 * (views[i].min_x + views[i].max_x) - 0.5 * (s.min_x + s.max_x);
    const double dy = 0.5 * (views[i].min_y + views[i].max_y) - 0.5 * (s.min_y + s.max_y);
    s = {s.min_x + dx, s.min_y + dy, s.max_x + dx, s.max_y + dy};
  }
  return cells;
}

}  // namespace lifelong::render
