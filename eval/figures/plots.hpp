// Figures in the style of the seed's Figs. 6.1-6.5: every mode on one chart, per
// observation. Drives the `gnuplot` binary with generated scripts and data files (kept in
// <out_dir>/plot_data/ so a figure can be re-made or restyled by hand). PNG terminal:
// pngcairo when gnuplot has it, else png. Every file is written atomically
// (io/atomic_file.hpp): gnuplot draws into "<name>.tmp.png", renamed when it succeeded.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "eval/common/gnuplot_run.hpp"
#include "eval/metrics/types.hpp"

namespace lifelong::eval {

struct PlotConfig {
  std::string gnuplot = "gnuplot";  ///< binary, looked up in PATH
  int moving_average = 25;          ///< observations in the trailing moving average
  bool log_time = false;            ///< log-scale y axis for the time per observation
  int width_px = 800;               ///< px
  int height_px = 500;              ///< px
  /// Legend (and drawing) order: these modes first, as given (the run's --modes, baseline
  /// first); any other mode after them by name.
  std::vector<std::string> mode_order;
  /// The directory that messages name (the output's final place when out_dir is a staging
  /// directory, eval/common/staged_output.hpp); empty: out_dir.
  std::string named_dir;
};

struct FailedFigure {
  std::string figure;  ///< e.g. "loop_closing.png"
  std::string log;     ///< gnuplot's messages: <named_dir>/plot_data/<name>.log
};

/// ok == false with a message (e.g. gnuplot missing, a figure failed) instead of an
/// exception: figures are optional output. `files` lists the PNGs written, with their
/// paths; `failed` the figures whose gnuplot script failed (the others are still written).
struct PlotResult {
  bool ok = false;
  std::string error;
  std::vector<std::string> files;
  std::vector<FailedFigure> failed;
  bool gnuplot_found = false;  ///< gnuplot ran (plot_data/ was made)
};

/// mode name -> its timeline.
using ModeTimelines = std::map<std::string, std::vector<TimelineRow>>;

/// Writes time_per_obs.png (raw as dots, moving average as lines), nodes.png, edges.png,
/// gamma.png, cumulative_time.png (the sum of time_ms, s) and memory.png (two panels: the
/// timeline's rss_mb and graph_bytes, both in MiB) into out_dir (which must exist); and two
/// in the seed's layout, panels side by side: performance.png (time per observation, nodes,
/// edges: Figs. 6.1-6.4) and edges_gamma.png (edges, gamma index: Fig. 6.5). Each mode is
/// drawn in its own colour (eval/figures/mode_colors.hpp).
PlotResult PlotTimelines(const ModeTimelines& timelines, const std::string& out_dir,
                         const PlotConfig& config = {});

/// Every figure of a run, in one gnuplot process when all succeed (eval/common/gnuplot_run.hpp):
/// PlotTimelines' figures; kld.png, the KL divergence of each marginalization per mode in
/// order; and loop_closing.png, cumulative loop-closure precision (top) and recall (bottom)
/// of each mode over robot time, points before the first closure (revisit) left out, on a
/// fixed 0-1 axis: a run without closures draws an empty chart saying "no closures". Each
/// figure when its data is not empty.
/// The scripts stay in plot_data/ and each re-makes its figure alone; gnuplot's messages go
/// to plot_data/gnuplot.log. A figure whose script fails is the only one lost: it leaves
/// plot_data/<name>.log and no <name>.png (eval/report/report_files.cpp reads that).
PlotResult PlotRun(const ModeTimelines& timelines,
                   const std::map<std::string, std::vector<double>>& kl_per_mode,
                   const std::map<std::string, std::vector<LoopCurvePoint>>& curves,
                   const std::string& out_dir, const PlotConfig& config = {});

}  // namespace lifelong::eval
