// report.html: one offline page (inline CSS, no scripts, relative links only) laid out for
// a reader of the seed's chapter 6, who looks first at the runtime and the graph size
// (Figs. 6.1-6.4) and the maps and graphs (Figs. 6.6-6.9): the banners of what makes the
// run doubtful (eval/report/report_alerts.hpp), the time per observation, nodes and edges charts,
// the maps and graphs of every mode side by side at one scale with the edge-colour legend,
// a compact table of the key figures with the full grouped table folded below it,
// published figures for the log, the other charts, links to every output file, and the
// provenance (version, commit, command line). Every figure has a caption and opens full
// size on click.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "eval/figures/reference_figures.hpp"
#include "eval/metrics/summary.hpp"
#include "eval/report/build_info.hpp"

namespace lifelong::eval {

struct ReportFigure {
  std::string path;     ///< relative to the page
  std::string caption;  ///< one or two sentences
  int width_px = 0;     ///< display size; 0: the stylesheet's
  int height_px = 0;
};

/// One cell of the maps' grid: a mode's map and its graph alone, or the truth's map.
struct ReportMapCard {
  std::string name;                   ///< the mode, or "ground truth"
  std::string colour;                 ///< the mode's "#rrggbb"; empty for the truth
  std::vector<ReportFigure> figures;  ///< the map, then the graph alone
};

struct ReportLink {
  std::string label;  ///< e.g. "timeline.csv"
  std::string path;   ///< relative to the page
};

struct ReportLinkGroup {
  std::string name;  ///< e.g. a mode, "truth", "run"
  std::vector<ReportLink> links;
};

struct ReportPage {
  std::string title = "lifelong report";
  RunSummary summary;
  std::string command_line;  ///< as typed
  std::string working_dir;   ///< where it was typed
  std::string machine;       ///< e.g. CpuModelName(); empty: read /proc/cpuinfo
  BuildInfo build;           ///< version and commit of the program
  std::string written_utc;   ///< e.g. "2026-12-01 16:23 UTC"
  std::string lead_heading = "Runtime and graph size";  ///< over the lead figures
  std::vector<ReportFigure> lead_figures;     ///< time per observation, nodes, edges: first
  std::vector<ReportFigure> figures;          ///< the other plots, further down
  std::vector<ReportLink> failed_figures;     ///< plots gnuplot failed on: figure, its log
  std::string figures_note;                   ///< why there is no plot at all; empty: there are
  std::map<std::string, std::string> maps;    ///< mode -> its map image (set while running)
  std::vector<ReportMapCard> map_cards;       ///< truth first, then the modes in order
  int map_columns = 1;                        ///< cards per row of the maps' grid
  std::string maps_note;                      ///< the maps' content, frame and scale
  bool true_path_in_maps = false;             ///< the legend lists the true trajectory
  std::vector<ReportFigure> change_strips;    ///< per mode, its changed objects (change_tiles)
  std::vector<ReportLinkGroup> files;         ///< links to the output files
  std::optional<ReferenceFigures> reference;  ///< published figures for this log
};

/// The page as HTML text.
std::string ReportHtmlText(const ReportPage& page);

/// Writes the page atomically. Throws std::runtime_error naming the path on failure.
void WriteReportHtml(const std::string& path, const ReportPage& page);

}  // namespace lifelong::eval
