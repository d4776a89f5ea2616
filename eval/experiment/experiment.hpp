// The experiments behind `lifelong run` and `lifelong replay`: feed one observation stream
// to every requested mode, measure each, and write the output contract of DESIGN.md.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eval/experiment/false_closures.hpp"
#include "eval/figures/run_maps.hpp"
#include "eval/figures/video.hpp"
#include "eval/metrics/summary.hpp"
#include "eval/report/report_files.hpp"
#include "eval/truth/ground_truth.hpp"
#include "sensor/observation.hpp"
#include "sim/world.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/mapping/mapper.hpp"
#include "slam/mapping/mapper_config.hpp"
#include "types/occupancy_grid.hpp"
#include "types/relation.hpp"
#include "types/segment.hpp"
#include "types/stamped_pose.hpp"

namespace lifelong::eval {

struct ExperimentConfig {
  std::vector<slam::Mode> modes{slam::NamedMode("standard"), slam::NamedMode("pruned")};
  slam::MapperConfig mapper;
  FalseClosureConfig false_closures;  ///< eval's test of the loop closer's defences (off)
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

/// The mapper's map as an OccupancyGrid: the counting grid's p = hits / (hits + misses), as
/// the world most likely stands at the latest scan (Mapper::ForEachPresentCell).
OccupancyGrid ToOccupancyGrid(const slam::Mapper& mapper);

/// What the report of a run of RunExperiment needs to know of it; `frame` is the run's
/// (MakeRunMapFrame).
ReportContext MakeReportContext(const ExperimentConfig& config, const RunMapFrame& frame,
                                const std::optional<GroundTruth>& truth,
                                const PlotConfig& plot_config);

/// Runs every mode over `stream` and writes DIR/summary.json, DIR/<mode>/..., figures and
/// report.html, all or nothing: into a staging directory beside DIR that replaces DIR only
/// once everything is written (eval/common/staged_output.hpp). `truth` enables the ground-truth
/// metrics. Throws Interrupted (eval/common/interrupt.hpp) after Ctrl-C, leaving DIR as it was.
RunSummary RunExperiment(const std::vector<Observation>& stream,
                         const std::optional<GroundTruth>& truth, const ExperimentConfig& config);

}  // namespace lifelong::eval
