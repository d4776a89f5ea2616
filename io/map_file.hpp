// Occupancy maps as ROS map_server files: a binary PGM (P5) image plus a YAML header
// (image, resolution, origin [x, y, yaw], negate, occupied_thresh, free_thresh).
// Image row 0 is the top of the map (highest y), so rows are flipped against the grid.
// Trinary pixels: occupied 0, free 254, unknown 205.
#pragma once

#include <string>

#include "io/occupancy_grid.hpp"

namespace lifelong::io {

struct MapFileConfig {
  double occupied_thresh = 0.65;  ///< p_occ above this is written occupied
  double free_thresh = 0.196;     ///< p_occ below this is written free
};

struct MapFilePaths {
  std::string pgm;
  std::string yaml;
};

/// Writes `<stem>.pgm` and `<stem>.yaml`; the argument may be the stem or the .pgm path.
/// Throws InputError when a file cannot be written.
MapFilePaths WritePgmMap(const std::string& stem_or_pgm_path, const OccupancyGrid& grid,
                         const MapFileConfig& config = {});

/// Reads a map_server YAML and its image (path relative to the YAML) in trinary mode:
/// occupied cells get p_occ 1, free 0, the rest OccupancyGrid::kUnknown. The origin's yaw
/// must be 0. Throws InputError naming the file, line and field on bad input.
OccupancyGrid ReadPgmMap(const std::string& yaml_path);

}  // namespace lifelong::io
