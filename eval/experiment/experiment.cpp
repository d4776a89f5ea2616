#include "eval/experiment/experiment.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "eval/common/interrupt.hpp"
#include "eval/common/progress.hpp"
#include "eval/common/resources.hpp"
#include "eval/common/staged_output.hpp"
#include "eval/common/stopwatch.hpp"
#include "eval/experiment/mapper_config_file.hpp"
#include "eval/experiment/mode_runner.hpp"
#include "eval/figures/draw.hpp"
#include "eval/figures/plots.hpp"
#include "eval/figures/run_maps.hpp"
#include "eval/figures/trajectory_figure.hpp"
#include "eval/figures/video.hpp"
#include "eval/metrics/metrics.hpp"
#include "eval/metrics/summary.hpp"
#include "eval/report/report_files.hpp"
#include "eval/truth/truth_raster.hpp"
#include "eval/truth/world_state.hpp"
#include "io/atomic_file.hpp"
#include "io/graph_file.hpp"
#include "io/map_file.hpp"
#include "io/relations.hpp"
#include "io/tum.hpp"
#include "slam/mapping/mapper.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

void Progress(const ExperimentConfig& c, const std::string& line) {
  if (c.progress) *c.progress << line << std::flush;
}

// Renders one frame with every mode side by side.
void AddVideoFrame(FrameSink* sink, const Observation& obs, const std::optional<GroundTruth>& truth,
                   const std::vector<std::unique_ptr<ModeRunner>>& runners) {
  std::vector<render::Panel> panels;
  for (const auto& r : runners) {
    const slam::Mapper& m = r->mapper();
    const Pose2 estimate = m.LastScanPose().T_world_robot;
    panels.push_back(MakePanel(r->name(), ToOccupancyGrid(m), m.graph(), m.values(), estimate,
                               m.observations()));
  }
  const std::vector<Segment> walls = truth ? truth->walls : std::vector<Segment>{};
  const Pose2 pose = obs.T_world_robot_true.value_or(Pose2());
  sink->AddFrame(MakeScene(walls, pose, obs.scan, std::move(panels)));
}

/// The truth with its raster, made here once for the run unless the caller made it.
std::optional<GroundTruth> Rasterized(const std::optional<GroundTruth>& truth,
                                      const std::vector<Observation>& stream, double resolution_m) {
  if (!truth || truth->raster) return truth;
  GroundTruth t = *truth;
  std::vector<Pose2> path;
  for (const Observation& o : stream) {
    if (o.T_world_robot_true) path.push_back(*o.T_world_robot_true);
  }
  t.raster = std::make_shared<const TruthRaster>(t, path, resolution_m);
  return t;
}

/// The truth's files; returns those the report shows and links, relative to the output
/// directory.
std::vector<std::string> WriteTruth(const std::vector<Observation>& stream,
                                    const GroundTruth& truth, const RunMapFrame& frame,
                                    const ExperimentConfig& config) {
  const std::string dir = (fs::path(config.out_dir) / "truth").string();
  std::vector<std::string> files = WriteTruthFiles(dir, stream, truth.raster->WallGrid(), frame);
  WriteTruthWalls(dir + "/", truth);
  for (std::string& f : files) f = "truth/" + f;
  return files;
}

}  // namespace

OccupancyGrid ToOccupancyGrid(const slam::Mapper& mapper) {
  OccupancyGrid grid;
  grid.resolution_m = mapper.map().resolution_m();
  const slam::CellBounds b = mapper.map().Bounds();
  if (b.empty) return grid;
  grid.width = b.max.x - b.min.x + 1;
  grid.height = b.max.y - b.min.y + 1;
  grid.origin_x_m = b.min.x * grid.resolution_m;
  grid.origin_y_m = b.min.y * grid.resolution_m;
  grid.p_occ.assign(static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height),
                    OccupancyGrid::kUnknown);
  mapper.ForEachPresentCell([&](slam::CellIndex c, double p) {
    grid.At(c.x - b.min.x, c.y - b.min.y) = static_cast<float>(p);
  });
  return grid;
}

namespace {

// Robot time from the first observation to the latest one so far (stamps may run
// backwards in real logs; the span never does).
class StreamSpan {
 public:
  explicit StreamSpan(const std::vector<Observation>& stream) : stream_(stream) {}
  double Covered(std::size_t done) {
    for (; seen_ < done; ++seen_) {
      lo_ = std::min(lo_, stream_[seen_].stamp_s);
      hi_ = std::max(hi_, stream_[seen_].stamp_s);
    }
    return seen_ == 0 ? 0.0 : hi_ - lo_;
  }

 private:
  const std::vector<Observation>& stream_;
  std::size_t seen_ = 0;
  double lo_ = std::numeric_limits<double>::infinity();
  double hi_ = -std::numeric_limits<double>::infinity();
};

ProgressOptions MeterOptions(const ExperimentConfig& c, const std::string& label) {
  ProgressOptions o;
  o.label = label;
  o.unit = "scans";
  o.terminal = c.progress_terminal;
  return o;
}

}  // namespace

namespace {

/// What the modes leave once each is finished: their summaries and everything the plots,
/// figures and report draw from.
struct ModeResults {
  RunSummary summary;
  ModeTimelines timelines;
  std::map<std::string, std::vector<double>> kld;
  std::map<std::string, std::vector<LoopCurvePoint>> loop_curves;
  std::vector<AlignedTrack> reference_tracks;
  ReportPage page;
  std::set<std::string> files;  ///< written, relative to the output directory
  RunMapFrame frame;            ///< the run's one scale and canvas of map figures

  /// Evaluates a mode, writes its outputs and frees its mapper.
  void Finish(ModeRunner* r, const std::vector<Observation>& stream,
              const std::optional<GroundTruth>& truth, const std::vector<Relation>& relations) {
    std::vector<double> kl;
    std::string map_png;
    summary.modes[r->name()] = r->Finish(stream, truth, relations, frame, &kl, &map_png);
    timelines[r->name()] = r->timeline();
    if (!kl.empty()) kld[r->name()] = std::move(kl);
    if (!r->loop_curve().empty()) loop_curves[r->name()] = r->loop_curve();
    if (!r->aligned_to_reference().empty()) {
      reference_tracks.push_back({r->name(), r->aligned_to_reference()});
    }
    page.maps[r->name()] = map_png;
    if (!r->changes_png().empty()) {
      page.change_strips.push_back({r->changes_png(), r->name() + ": " + r->changes_caption()});
    }
    files.insert(r->written().begin(), r->written().end());
    r->Release();
  }
};

std::unique_ptr<FrameSink> OpenFrameSink(const ExperimentConfig& config) {
  if (config.video_path.empty() && config.frames_dir.empty()) return nullptr;
  if (!config.open_video) throw std::logic_error("RunExperiment: frames asked for, no sink");
  VideoOptions options;
  options.video_path = config.video_path;
  options.frames_dir = config.frames_dir;
  options.stride = config.video_stride;
  std::unique_ptr<FrameSink> sink = config.open_video(options);
  Progress(config, "rendering with " + sink->backend_name() + "\n");
  return sink;
}

using Runners = std::vector<std::unique_ptr<ModeRunner>>;

/// Lockstep, for a video: every mode sees scan i before any sees scan i + 1.
void RunLockstep(const std::vector<Observation>& stream, const std::optional<GroundTruth>& truth,
                 const ExperimentConfig& config, FrameSink* sink, Runners& runners,
                 ModeResults* results) {
  const std::size_t n = stream.size();
  StreamSpan span(stream);
  ProgressMeter meter(config.progress, static_cast<double>(n), MeterOptions(config, "all modes"));
  for (std::size_t i = 0; i < n; ++i) {
    ThrowIfInterrupted();
    for (auto& r : runners) {
      r->Step(stream[i]);
      r->ScorePresentAt(stream, i, truth);
    }
    if (sink->Wants(static_cast<int>(i))) AddVideoFrame(sink, stream[i], truth, runners);
    meter.Update(static_cast<double>(i + 1), span.Covered(i + 1),
                 runners.front()->ProgressDetail());
  }
  sink->Close();
  meter.Finish(span.Covered(n), runners.front()->ProgressDetail());
  for (auto& r : runners) results->Finish(r.get(), stream, truth, config.relations);
}

/// One mode after the other, each with its own peak RSS.
void RunInTurn(const std::vector<Observation>& stream, const std::optional<GroundTruth>& truth,
               const ExperimentConfig& config, Runners& runners, ModeResults* results) {
  const std::size_t n = stream.size();
  for (auto& r : runners) {
    ResetPeakRss();
    StreamSpan span(stream);
    ProgressMeter meter(config.progress, static_cast<double>(n), MeterOptions(config, r->name()));
    for (std::size_t i = 0; i < n; ++i) {
      ThrowIfInterrupted();
      r->Step(stream[i]);
      r->ScorePresentAt(stream, i, truth);
      meter.Update(static_cast<double>(i + 1), span.Covered(i + 1), r->ProgressDetail());
    }
    meter.Finish(span.Covered(n), r->ProgressDetail());
    results->Finish(r.get(), stream, truth, config.relations);
  }
}

/// reference/trajectory.tum: the log's reference poses (a corrected log's own, or
/// --reference), so that a tool outside can score the modes' trajectories against them as
/// against a run's truth/trajectory.tum; whether it was written.
bool WriteReferenceTrajectory(const ExperimentConfig& config) {
  if (config.reference.empty()) return false;
  const fs::path dir = fs::path(config.out_dir) / "reference";
  fs::create_directories(dir);
  io::WriteTum((dir / "trajectory.tum").string(), config.reference);
  return true;
}

/// trajectories.png: the modes aligned to the log's reference trajectory, when it has one;
/// whether it was written.
bool WriteReferenceFigure(const ExperimentConfig& config, const std::vector<AlignedTrack>& tracks) {
  if (tracks.empty()) return false;
  std::vector<Pose2> reference;
  for (const StampedPose& p : config.reference) reference.push_back(p.T_world_robot);
  const std::string name =
      config.log && config.log->reference ? *config.log->reference : std::string("reference");
  WriteTrajectoryFigure((fs::path(config.out_dir) / "trajectories.png").string(), reference,
                        "reference: " + name, tracks);
  return true;
}

}  // namespace

RunSummary RunExperiment(const std::vector<Observation>& stream,
                         const std::optional<GroundTruth>& given_truth,
                         const ExperimentConfig& final_config) {
  const auto start = Clock::now();
  const double res = final_config.mapper.grid.resolution_m;
  const std::optional<GroundTruth> truth = Rasterized(given_truth, stream, res);
  StagedOutput output(final_config.out_dir);
  ExperimentConfig config = final_config;
  config.out_dir = output.path();
  io::WriteFileAtomically((fs::path(config.out_dir) / "config.yaml").string(),
                          "# Settings of this run (lifelong --config format)\n" +
                              MapperConfigToYaml(config.mapper, config.false_closures));
  const std::unique_ptr<FrameSink> sink = OpenFrameSink(config);
  Runners runners;
  for (const slam::Mode& mode : config.modes) {
    runners.push_back(std::make_unique<ModeRunner>(mode, config));
  }
  ModeResults results;
  RunSummary& summary = results.summary;
  summary.source = config.source;
  summary.seed = config.seed;
  summary.log = config.log;
  summary.simulation = config.simulation;
  if (!stream.empty()) summary.log_duration_s = StreamSpan(stream).Covered(stream.size());
  for (const auto& r : runners) summary.mode_order.push_back(r->name());
  results.frame = MakeRunMapFrame(stream, truth ? &truth->walls : nullptr, res);
  if (sink) {
    RunLockstep(stream, truth, config, sink.get(), runners, &results);
  } else {
    RunInTurn(stream, truth, config, runners, &results);
  }
  ThrowIfInterrupted();
  results.files.insert("config.yaml");
  if (truth) {
    const std::vector<std::string> written = WriteTruth(stream, *truth, results.frame, config);
    results.files.insert(written.begin(), written.end());
  }
  if (WriteReferenceTrajectory(config)) results.files.insert("reference/trajectory.tum");
  if (WriteReferenceFigure(config, results.reference_tracks)) {
    results.files.insert("trajectories.png");
  }
  PlotConfig plot_config;
  plot_config.log_time = true;  // the modes differ by orders of magnitude
  plot_config.mode_order = summary.mode_order;
  plot_config.named_dir = final_config.out_dir;  // the staging directory is gone by then
  const PlotResult plots =
      PlotRun(results.timelines, results.kld, results.loop_curves, config.out_dir, plot_config);
  if (!plots.ok) Progress(config, "warning: " + plots.error + "\n");
  ThrowIfInterrupted();
  summary.wall_time_s = Seconds(start);
  ReportPage& page = results.page;
  page.summary = summary;
  page.command_line = config.command_line;
  ReportContext context = MakeReportContext(config, results.frame, truth, plot_config);
  context.files = std::move(results.files);
  for (const std::string& png : plots.files) context.files.insert(fs::path(png).filename());
  for (const FailedFigure& f : plots.failed) context.failed_plots.push_back(f.figure);
  context.gnuplot_ran = plots.gnuplot_found;
  CompleteReportPage(context, &page);
  WriteReportHtml((fs::path(config.out_dir) / "report.html").string(), page);
  WriteSummaryJson((fs::path(config.out_dir) / "summary.json").string(), summary);
  output.Commit();
  return summary;
}

ReportContext MakeReportContext(const ExperimentConfig& config, const RunMapFrame& frame,
                                const std::optional<GroundTruth>& truth,
                                const PlotConfig& plot_config) {
  ReportContext c;
  c.out_dir = config.out_dir;
  c.map_m_per_px = frame.m_per_px;
  c.truth_frame = truth.has_value();
  c.moving_average = plot_config.moving_average;
  c.log_time = plot_config.log_time;
  c.relations_path = config.relations_path.value_or("");
  return c;
}

}  // namespace lifelong::eval
