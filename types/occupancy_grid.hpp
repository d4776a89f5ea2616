// A probability grid as exchanged between eval (made from slam's grid map; metrics,
// drawing), io (PGM + YAML files) and render (a panel's map). Row 0 is the lowest y; cell
// (col,row) covers [origin_x_m + col*res, origin_x_m + (col+1)*res) x [origin_y_m + row*res, ...).
#pragma once

#include <cstddef>
#include <vector>

namespace lifelong {

struct OccupancyGrid {
  int width = 0;               ///< cells along x
  int height = 0;              ///< cells along y
  double resolution_m = 0.05;  ///< m per cell
  double origin_x_m = 0.0;     ///< world x of the lower-left corner of cell (0,0)
  double origin_y_m = 0.0;     ///< world y of the lower-left corner of cell (0,0)
  std::vector<float> p_occ;    ///< row-major, width*height; < 0 means unknown

  static constexpr float kUnknown = -1.0f;

  bool Contains(int col, int row) const {
    return col >= 0 && row >= 0 && col < width && row < height;
  }
  float At(int col, int row) const {
    return p_occ[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(col)];
  }
  float& At(int col, int row) {
    return p_occ[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(col)];
  }
};

}  // namespace lifelong
