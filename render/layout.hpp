// Where each view goes in the frame: the world view first, then one view per panel, in a
// grid of equal cells whose column count gives the largest common scale for the shown
// world region. Every cell has a title strip above its view. Pure arithmetic, no GL.
#pragma once

#include <cstddef>
#include <vector>

#include "render/scene.hpp"

namespace lifelong::render {

/// A pixel rectangle, x to the right and y down from the frame's top-left corner.
struct Rect {
  int x = 0, y = 0, width = 0, height = 0;
};

struct Cell {
  Rect title;    ///< title strip (text lines go here)
  Rect view;     ///< the drawn view
  Bounds shown;  ///< world region mapped onto `view`: the requested one, centred and
                 ///< widened along one axis so that metres per pixel is the same in x and y
};

struct LayoutConfig {
  int width_px = 1280;  ///< frame width
  int height_px = 720;  ///< frame height
  int title_px = 40;    ///< height of the title strip above each view
  int margin_px = 4;    ///< gap around each view, pixels
};

/// Lays out `cells` cells showing `world` (non-empty). Cells fill rows left to right.
std::vector<Cell> ComputeLayout(std::size_t cells, const Bounds& world, const LayoutConfig& config);

/// One cell per entry of `views`, at one scale: the grid is laid out for a region as wide
/// and as tall as the largest view, and each cell is centred on its own view.
std::vector<Cell> ComputeLayout(const std::vector<Bounds>& views, const LayoutConfig& config);

}  // namespace lifelong::render
