#include "eval/report/report_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>

#include "eval/figures/mode_colors.hpp"
#include "eval/figures/run_maps.hpp"
#include "eval/report/report_table.hpp"
#include "slam/mapping/mapper_config.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

std::string Num(double v, const char* fmt) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

/// The plots in the order of the seed's chapter 6, with their captions; the first three
/// lead the page.
std::vector<std::pair<const char*, std::string>> PlotCaptions(const ReportContext& c) {
  const std::string ma = std::to_string(c.moving_average);
  return {
      {"time_per_obs.png",
       "Mapper time per observation: dots each observation, lines the moving average over " + ma +
           (c.log_time ? " (log scale)" : "") + ". Seed Figs. 6.1-6.4, left."},
      {"nodes.png",
       "Graph nodes. Seed Figs. 6.1-6.4, middle: pruning holds them to the size of the "
       "mapped area."},
      {"edges.png",
       "Graph edges (a dense clique over m nodes counts m(m-1)/2). Seed Figs. 6.1-6.4, "
       "right."},
      {"cumulative_time.png",
       "Cumulative mapper time, s. The seed compares these totals (Intel: 537 s standard vs "
       "314 s pruned)."},
      {"memory.png",
       "Memory. Top: resident memory of the whole process (the observation stream "
       "included). Bottom: memory held by the graph, log scale."},
      {"gamma.png",
       "Gamma index e / (v(v-1)/2), log scale (seed eq. 6.1, Fig. 6.5): exact "
       "marginalization makes the graph dense, Chow-Liu trees keep it sparse."},
      {"loop_closing.png",
       "Loop closing against the truth: cumulative precision of the accepted closures and "
       "recall of the revisits (correct: within 0.3 m and 5 deg)."},
      {"trajectories.png",
       "The log's reference trajectory (black) and each mode's estimate moved onto it by its "
       "ATE alignment: where the map bends or a loop stays open, the tracks part."},
      {"kld.png",
       "KL divergence of each marginalization's approximate clique from the exact marginal, "
       "nats, in removal order (exact: 0)."},
  };
}

constexpr std::size_t kLeadPlots = 3;  // time per observation, nodes, edges

/// The plots drawn, and those whose gnuplot script failed (eval/figures/plots.hpp: the script is
/// in plot_data/, its messages in plot_data/<name>.log, and there is no <name>.png).
void Plots(const ReportContext& c, ReportPage* page) {
  page->lead_figures.clear(), page->figures.clear(), page->failed_figures.clear();
  page->figures_note.clear();
  const auto plots = PlotCaptions(c);
  for (std::size_t i = 0; i < plots.size(); ++i) {
    const std::string file = plots[i].first;
    const std::string stem = fs::path(file).stem().string();
    if (c.files.count(file)) {
      (i < kLeadPlots ? page->lead_figures : page->figures)
          .push_back({file, plots[i].second, 0, 0});
    } else if (std::count(c.failed_plots.begin(), c.failed_plots.end(), file)) {
      page->failed_figures.push_back({file, "plot_data/" + stem + ".log"});
    }
  }
  if (page->lead_figures.empty() && page->figures.empty() && page->failed_figures.empty()) {
    page->figures_note = c.gnuplot_ran
                             ? "No charts were drawn: gnuplot failed (see plot_data/gnuplot.log)."
                             : "No charts were drawn: gnuplot was not found when this run was "
                               "made (the run printed a warning). Install gnuplot and run again.";
  }
}

std::string GraphSize(const ModeSummary& m) {
  if (!m.nodes_final || !m.edges_final) return "";
  return std::to_string(*m.nodes_final) + " nodes, " + std::to_string(*m.edges_final) + " edges";
}

/// Height of a card of the maps' grid: its images at `factor`, plus its title and
/// captions (px, as the stylesheet lays them out).
double CardHeight(const ReportMapCard& card, double factor) {
  constexpr double kTitlePx = 26.0, kCaptionPx = 20.0;
  double h = kTitlePx;
  for (const ReportFigure& f : card.figures) h += f.height_px * factor + kCaptionPx;
  return h;
}

/// The columns of the maps' grid and the one display factor of all its images. Of the
/// grids that fit max_maps_height_px, the one with the largest images for the share of its
/// cells filled (factor x cards / cells: four cards in one row rather than three and one
/// left alone); when none fits, the lowest.
std::pair<int, double> MapGrid(const std::vector<ReportMapCard>& cards, const ReportContext& c) {
  int max_w = 0, max_h = 0;
  for (const ReportMapCard& card : cards)
    for (const ReportFigure& f : card.figures)
      max_w = std::max(max_w, f.width_px), max_h = std::max(max_h, f.height_px);
  constexpr double kGapPx = 16.0;
  std::pair<int, double> best{1, 1.0}, best_fit{0, 0.0};
  double best_height = std::numeric_limits<double>::max(), best_score = 0.0;
  const int n = static_cast<int>(cards.size());
  for (int k = 1; k <= std::max(n, 1); ++k) {
    double factor = 1.0;
    if (max_w > 0) factor = std::min(factor, ((c.page_width_px - (k - 1) * kGapPx) / k) / max_w);
    if (max_h > 0) factor = std::min(factor, static_cast<double>(c.max_map_height_px) / max_h);
    double height = 0.0;
    for (int row = 0; row * k < n; ++row) {
      double row_height = 0.0;
      for (int i = row * k; i < std::min(n, row * k + k); ++i)
        row_height = std::max(row_height, CardHeight(cards[i], factor));
      height += row_height + kGapPx;
    }
    const int rows = (n + k - 1) / k;
    const double score = factor * n / std::max(rows * k, 1);
    if (height <= c.max_maps_height_px && score > best_score)
      best_score = score, best_fit = {k, factor};
    if (height < best_height) best_height = height, best = {k, factor};
  }
  return best_fit.first > 0 ? best_fit : best;
}

/// Map and graph of each mode in one card, the truth's first, every image at one display
/// factor, in the columns MapGrid chooses.
void MapFigures(const ReportContext& c, ReportPage* page) {
  const std::string scale = "1 px = " + Num(c.map_m_per_px * 100.0, "%.3g") + " cm";
  const fs::path dir(c.out_dir);
  const auto figure = [&](const std::string& path, const std::string& caption) {
    const auto [w, h] = PngSize((dir / path).string());
    return ReportFigure{path, caption, w, h};
  };
  std::vector<ReportMapCard> cards;
  if (c.files.count("truth/map.png")) {
    cards.push_back({"ground truth", "", {figure("truth/map.png", "walls, doors, boxes, path")}});
  }
  for (const std::string& mode : OrderedModes(page->summary)) {
    ReportMapCard card{mode, ModeColourHex(mode), {}};
    const std::string size = GraphSize(page->summary.modes.at(mode));
    const auto map = page->maps.find(mode);
    if (map != page->maps.end() && c.files.count(map->second)) {
      card.figures.push_back(
          figure(map->second, "map and graph" + (size.empty() ? "" : ", " + size)));
    }
    const std::string graph = "graph_" + mode + ".png";
    if (c.files.count(graph)) card.figures.push_back(figure(graph, "the graph alone"));
    if (!card.figures.empty()) cards.push_back(std::move(card));
  }
  const auto [columns, factor] = MapGrid(cards, c);
  for (ReportMapCard& card : cards) {
    for (ReportFigure& f : card.figures) {
      f.width_px = static_cast<int>(std::lround(f.width_px * factor));
      f.height_px = static_cast<int>(std::lround(f.height_px * factor));
    }
  }
  page->map_cards = std::move(cards);
  page->map_columns = columns;
  page->true_path_in_maps = c.truth_frame;
  page->maps_note =
      (c.truth_frame
           ? "Each mode's occupancy grid (black: hit at least as often as passed through; grey: "
             "unknown) with its final graph, moved into the world frame by its ATE alignment, "
             "over the true path; below it the graph alone (seed Fig. 6.6). All share one box "
             "(what the laser saw, plus 1 m) and one scale: "
           : "Each mode's occupancy grid (black: hit at least as often as passed through; grey: "
             "unknown) with its final graph in the mapper's frame (no ground truth), cropped to "
             "its known cells; below it the graph alone (seed Fig. 6.6). All share one scale: ") +
      scale + " in the files, shown here at " + Num(factor * 100.0, "%.0f") +
      " %; click a map for full size.";
}

/// A link for each of `names` (in `dir`) that the run wrote.
ReportLinkGroup Links(const ReportContext& c, const std::string& name, const std::string& dir,
                      const std::vector<std::string>& names) {
  ReportLinkGroup g{name, {}};
  for (const std::string& f : names) {
    const std::string rel = dir.empty() ? f : dir + "/" + f;
    if (c.files.count(rel)) g.links.push_back({f, rel});
  }
  return g;
}

std::vector<ReportLinkGroup> FileLinks(const ReportContext& c, const ReportPage& page) {
  std::vector<ReportLinkGroup> out;
  ReportLinkGroup run = Links(c, "run", "", {"config.yaml"});
  // summary.json is written right after this page and is the one link made before its
  // file exists: it is the run's main output, and a run that fails in between leaves no
  // summary.json (docs/output-contract.md), which marks the whole directory as incomplete anyway.
  run.links.insert(run.links.begin(), {"summary.json", "summary.json"});
  out.push_back(run);
  for (const std::string& mode : OrderedModes(page.summary)) {
    ReportLinkGroup g = Links(c, mode, mode,
                              {"timeline.csv", "marginalizations.csv", "sparsifications.csv",
                               "graph.g2o", "trajectory.tum", "map.pgm", "map.yaml", "map.png"});
    const ReportLinkGroup graph = Links(c, mode, "", {"graph_" + mode + ".png"});
    g.links.insert(g.links.end(), graph.links.begin(), graph.links.end());
    if (!g.links.empty()) out.push_back(g);
  }
  ReportLinkGroup truth =
      Links(c, "ground truth", "truth", {"trajectory.tum", "map.pgm", "map.yaml", "map.png"});
  if (!truth.links.empty()) out.push_back(truth);
  ReportLinkGroup reference = Links(c, "reference", "reference", {"trajectory.tum"});
  if (!reference.links.empty()) out.push_back(reference);
  return out;
}

std::string NowUtc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[64];
  std::strftime(buf, sizeof(buf), "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

}  // namespace

std::pair<int, int> PngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  if (!in.read(reinterpret_cast<char*>(h), sizeof(h))) return {0, 0};
  const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!std::equal(magic, magic + 8, h) || std::string(h + 12, h + 16) != "IHDR") return {0, 0};
  const auto be32 = [&](int i) {
    return static_cast<int>((h[i] << 24) | (h[i + 1] << 16) | (h[i + 2] << 8) | h[i + 3]);
  };
  return {be32(16), be32(20)};
}

void CompleteReportPage(const ReportContext& context, ReportPage* page) {
  Plots(context, page);
  MapFigures(context, page);
  page->files = FileLinks(context, *page);
  page->reference = FindReferenceFigures(context.relations_path, page->summary.source);
  page->build = GetBuildInfo();
  std::error_code ec;
  page->working_dir = fs::current_path(ec).string();
  page->written_utc = NowUtc();
}

}  // namespace lifelong::eval
