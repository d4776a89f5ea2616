// The experiments behind `lifelong run` and `lifelong replay`: feed one observation stream
// to every requested mode, measure each, and write the output contract of DESIGN.md.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "sensor/observation.hpp"
#include "slam/grid_map.hpp"
#include "slam/mapper_config.hpp"
#include "types/occupancy_grid.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

/// What is known of the truth (simulation only).
struct GroundTruth {
  std::vector<Segment> walls;  ///< static walls and doors, world frame
};

struct ExperimentConfig {
  std::vector<slam::PruningMode> modes{slam::PruningMode::kNone, slam::PruningMode::kChowLiu};
  slam::MapperConfig mapper = slam::DefaultMapperConfig();
  std::string out_dir;
  std::string source;                ///< scenario or log path, for the summary
  std::optional<std::int64_t> seed;  ///< simulation seed
  std::optional<std::string> relations_path;
  double relations_offset_s = 0.0;     ///< relation time = log time + this
  std::optional<double> first_pass_s;  ///< observations before this time form the first pass
  std::string command_line;
  std::ostream* progress = nullptr;  ///< progress lines; nullptr: quiet
  /// Video (--video FILE.mp4) and/or PNG frames (--frames DIR): the modes then run in
  /// lockstep, scan by scan, so that each frame shows every mode side by side.
  std::string video_path;
  std::string frames_dir;
  int video_stride = 20;  ///< render every this many scans
};

/// A short table of the key figures per mode, from RunExperiment's JSON, for the console.
std::string SummaryTable(const std::string& summary_json);

/// The mapper's counting grid as an OccupancyGrid (p = hits / (hits + misses)).
OccupancyGrid ToOccupancyGrid(const slam::GridMap& map);

/// Runs every mode over `stream` and writes DIR/summary.json, DIR/<mode>/..., figures and
/// report.html. `truth` enables the ground-truth metrics. Returns the summary's JSON text.
std::string RunExperiment(const std::vector<Observation>& stream,
                          const std::optional<GroundTruth>& truth, const ExperimentConfig& config);

}  // namespace lifelong::eval
