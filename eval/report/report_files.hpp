// Gathers what report.html shows from a finished output directory: the plots that were
// written (in the seed's order, each with its caption) and those that failed (with their
// gnuplot log), the maps and graphs (truth first, then the modes in run order, each
// mode's map and graph in one card, all shown at one display scale in a grid of as many
// columns as keep it low), links to the output files that exist, the published figures
// for the log and the provenance.
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "eval/figures/plots.hpp"
#include "eval/report/report_html.hpp"

namespace lifelong::eval {

struct ReportContext {
  std::string out_dir;  ///< the output directory; the page's links are relative to it
  /// The files the run's writers wrote, relative to out_dir: the page shows and links these
  /// and no others (summary.json, written after the page, is always linked).
  std::set<std::string> files;
  std::vector<std::string> failed_plots;  ///< plots whose gnuplot script failed (name.png)
  bool gnuplot_ran = false;               ///< gnuplot was found (then no chart means it failed)
  double map_m_per_px = 0.05;     ///< m per pixel of every map figure (eval/figures/run_maps.hpp)
  bool truth_frame = false;       ///< maps drawn in the truth frame (runs with ground truth)
  int moving_average = 25;        ///< observations in time_per_obs.png's moving average
  bool log_time = true;           ///< time_per_obs.png has a log y axis
  std::string relations_path;     ///< --relations file; empty without
  int page_width_px = 1340;       ///< px across the page's content (1400 px window)
  int max_map_height_px = 640;    ///< px, a map at most this tall (full size on click)
  int max_maps_height_px = 1300;  ///< px, the maps' grid at most this tall if it can
};

/// Fills page->lead_figures, figures, failed_figures, figures_note,
/// map_cards, map_columns, maps_note, true_path_in_maps, files, reference, build,
/// working_dir and written_utc. Needs
/// page->summary and maps (mode -> map image, relative to out_dir) to be set.
void CompleteReportPage(const ReportContext& context, ReportPage* page);

/// Width and height of a PNG from its header; {0, 0} when it is not a readable PNG.
std::pair<int, int> PngSize(const std::string& path);

}  // namespace lifelong::eval
