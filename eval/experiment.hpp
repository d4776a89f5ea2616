// The experiments behind `lifelong run` and `lifelong replay`: feed one observation stream
// to every requested mode, measure each, and write the output contract of DESIGN.md.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eval/report.hpp"
#include "eval/video.hpp"
#include "sensor/observation.hpp"
#include "sim/world.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/mapping/mapper_config.hpp"
#include "types/occupancy_grid.hpp"
#include "types/relation.hpp"
#include "types/segment.hpp"
#include "types/stamped_pose.hpp"

namespace lifelong::eval {

/// What is known of the truth (simulation only).
struct GroundTruth {
  /// Every surface that stood during the run (TrueWalls), world frame: blur and recall.
  std::vector<Segment> walls;
  /// The surfaces standing at the run's end (WallsAt) and those gone by then (GoneSurfaces):
  /// current_blur, current_recall and stale_cells. Empty gone: the world did not change.
  std::vector<Segment> walls_now;
  std::vector<Segment> gone;
  /// The simulated world and the run's end, for change_recall (eval/change_recall.hpp);
  /// none when the truth came from files.
  std::shared_ptr<const sim::World> world;
  double end_s = 0.0;
};

struct ExperimentConfig {
  std::vector<slam::PruningMode> modes{slam::PruningMode::kNone, slam::PruningMode::kChowLiu};
  slam::MapperConfig mapper;
  std::string out_dir;
  std::string source;                ///< scenario or log path, for the summary
  std::optional<std::int64_t> seed;  ///< simulation seed
  /// Relations in log time (io::ShiftRelations already applied); empty: none.
  std::vector<Relation> relations;
  std::optional<std::string> relations_path;  ///< the file they came from (report, figures)
  /// A reference trajectory (replay): ATE and RPE at 1 m are scored against it.
  std::vector<StampedPose> reference;
  /// reference[i] is the pose of scan i (a corrected log's own poses): paired by index,
  /// whatever the stamps say (some logs stamp every scan 0). Else paired by stamp.
  bool reference_per_scan = false;
  std::optional<LogInfo> log;                   ///< replay: what was read from the log
  std::optional<SimulationOutcome> simulation;  ///< run: what happened in the simulator
  std::optional<double> first_pass_s;  ///< observations before this time form the first pass
  /// run --present-at: times (s) at which each mode's map of the present is scored too
  /// (ModeSummary::present_at); ascending.
  std::vector<double> present_at_s;
  std::string command_line;
  std::ostream* progress = nullptr;  ///< progress lines; nullptr: quiet
  bool progress_terminal = false;    ///< progress goes to a terminal: redraw one line
  /// Video (--video FILE.mp4) and/or PNG frames (--frames DIR): the modes then run in
  /// lockstep, scan by scan, so that each frame shows every mode side by side.
  std::string video_path;
  std::string frames_dir;
  int video_stride = 20;  ///< render every this many scans
  /// Makes the sink for video_path / frames_dir: eval::OpenVideoSink, or the one of the
  /// module liblifelong_video.so that `lifelong` loads. Needed when either is set.
  FrameSinkOpener open_video;
};

/// The mapper's counting grid as an OccupancyGrid (p = hits / (hits + misses)).
OccupancyGrid ToOccupancyGrid(const slam::GridMap& map);

/// Runs every mode over `stream` and writes DIR/summary.json, DIR/<mode>/..., figures and
/// report.html, all or nothing: into a staging directory beside DIR that replaces DIR only
/// once everything is written (eval/staged_output.hpp). `truth` enables the ground-truth
/// metrics. Throws Interrupted (eval/interrupt.hpp) after Ctrl-C, leaving DIR as it was.
RunSummary RunExperiment(const std::vector<Observation>& stream,
                         const std::optional<GroundTruth>& truth, const ExperimentConfig& config);

}  // namespace lifelong::eval
