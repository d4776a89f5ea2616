// The most cells a dense raster of a run may hold: the map written as map.pgm and drawn in
// the figures, and the world's truth map, take 4 bytes a cell (1 GiB here; 820 m square at
// 5 cm). Inputs that would need more are refused before the work that would exhaust memory.
#pragma once

namespace lifelong::eval {

inline constexpr double kMaxRasterCells = double{1 << 28};

}  // namespace lifelong::eval
