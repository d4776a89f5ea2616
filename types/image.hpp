// An 8-bit RGB image, as the renderer reads it back (render) and the map drawing produces
// it (eval). Row 0 is the top row, as in PNG.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace lifelong {

struct Image {
  int width = 0;                  ///< pixels
  int height = 0;                 ///< pixels
  std::vector<std::uint8_t> rgb;  ///< row-major, 3 bytes per pixel (R, G, B), top row first

  /// The pixel in column x, row y (0 at the top).
  std::array<std::uint8_t, 3> Pixel(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                           static_cast<std::size_t>(x)) *
                          3u;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

}  // namespace lifelong
