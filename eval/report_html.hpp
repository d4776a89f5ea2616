// report.html: one offline page (inline CSS, no scripts, relative links only) laid out as a
// reader of the seed's chapter 6 expects: the grouped summary table, published figures for
// the log, the timeline plots (Figs. 6.1-6.5), the maps and the graphs alone (Figs.
// 6.6-6.9) at one scale with the edge-colour legend beside them, links to every output
// file, and the provenance (version, commit, command line). Every figure has a caption and
// opens full size on click.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "eval/build_info.hpp"
#include "eval/reference_figures.hpp"
#include "eval/report.hpp"

namespace lifelong::eval {

struct ReportFigure {
  std::string path;     ///< relative to the page
  std::string caption;  ///< one or two sentences
  int width_px = 0;     ///< display size; 0: the stylesheet's
  int height_px = 0;
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
  std::vector<std::string> mode_order;      ///< the run's --modes order; the first is the baseline
  std::string command_line;                 ///< as typed
  std::string working_dir;                  ///< where it was typed
  std::string machine;                      ///< e.g. CpuModelName(); empty: read /proc/cpuinfo
  BuildInfo build;                          ///< version and commit of the program
  std::string written_utc;                  ///< e.g. "2026-12-01 16:23 UTC"
  std::vector<ReportFigure> figures;        ///< the timeline plots
  std::map<std::string, std::string> maps;  ///< mode -> its map image (set while running)
  std::vector<ReportFigure> map_figures;    ///< truth first, then the modes in order
  std::vector<ReportFigure> graph_figures;  ///< the graphs alone, modes in order
  std::string maps_note;                    ///< the maps' frame and scale, one sentence
  bool true_path_in_maps = false;           ///< the legend lists the true trajectory
  std::vector<ReportLinkGroup> files;       ///< links to the output files
  std::optional<ReferenceFigures> reference;  ///< published figures for this log
};

/// The page as HTML text.
std::string ReportHtmlText(const ReportPage& page);

/// Writes the page atomically. Throws std::runtime_error naming the path on failure.
void WriteReportHtml(const std::string& path, const ReportPage& page);

}  // namespace lifelong::eval
