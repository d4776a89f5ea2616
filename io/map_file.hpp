// Occupancy maps as ROS map_server files: a binary PGM (P5) image plus a YAML header
// (image, resolution, origin [x, y, yaw], negate, occupied_thresh, free_thresh).
// Image row 0 is the top of the map (highest y), so rows are flipped against the grid.
// Trinary pixels: occupied 0, free 254, unknown 205.
#pragma once

#include <iosfwd>
#include <string>

#include "types/occupancy_grid.hpp"

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
/// must be 0, and the image a regular file (no device, FIFO or folder). Throws InputError
/// naming the file, line and field on bad input.
OccupancyGrid ReadPgmMap(const std::string& yaml_path);

/// What ReadPgmMap takes from the YAML (flat `key: value` lines, `#` comments).
struct MapYaml {
  std::string image;           ///< image path as written, relative to the YAML's folder
  int image_line = 0;          ///< line of `image:`, for errors about the image file
  double resolution_m = 0.05;  ///< m per cell, > 0
  double origin_x_m = 0.0;     ///< m, world x of the lower-left corner of the image
  double origin_y_m = 0.0;     ///< m, world y of the lower-left corner of the image
  bool negate = false;         ///< true: bright pixels are occupied
  MapFileConfig thresholds;    ///< occupied_thresh / free_thresh as read
};

/// The two halves of ReadPgmMap, on streams; `name` stands for the file in error messages.
/// ParsePgmImage reads the P5 header and then only width*height pixel bytes, so memory
/// grows with the bytes actually present, not with the size the header claims.
MapYaml ParseMapYaml(std::istream& in, const std::string& name);
OccupancyGrid ParsePgmImage(std::istream& in, const std::string& name, const MapYaml& yaml);

}  // namespace lifelong::io
