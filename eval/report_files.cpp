#include "eval/report_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "eval/report_table.hpp"
#include "eval/run_maps.hpp"
#include "slam/mapper_config.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

std::string Num(double v, const char* fmt) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

/// The plots in the order of the seed's chapter 6, with their captions.
std::vector<ReportFigure> Plots(const ReportContext& c) {
  const std::string ma = std::to_string(c.moving_average);
  const std::vector<std::pair<const char*, std::string>> plots = {
      {"time_per_obs.png",
       "Mapper time per observation: each observation as a dot, the moving average over " + ma +
           " observations as a line" + (c.log_time ? ", log scale" : "") +
           ". Seed Figs. 6.1-6.4, left."},
      {"nodes.png",
       "Graph nodes after each observation. Seed Figs. 6.1-6.4, middle: pruning holds the "
       "node count to the size of the mapped area."},
      {"edges.png",
       "Graph edges after each observation (a dense clique over m nodes counts m(m-1)/2). "
       "Seed Figs. 6.1-6.4, right."},
      {"cumulative_time.png",
       "Cumulative mapper time: the sum of the time per observation, in seconds. The seed "
       "compares these totals (e.g. Intel: 537 s standard vs 314 s pruned)."},
      {"memory.png",
       "Memory after each observation. Top: resident memory of the whole process (the "
       "observation stream included; with --video all modes share it). Bottom: memory held "
       "by the graph, log scale."},
      {"gamma.png",
       "Gamma index e / (v(v-1)/2) after each observation, log scale (seed eq. 6.1, Fig. "
       "6.5): exact marginalization makes the graph dense, Chow-Liu trees keep it sparse."},
      {"loop_closing.png",
       "Loop closing against the truth over the run: cumulative precision of the accepted "
       "closures (by their current node's time; precision is what keeps a map safe) and "
       "recall of the revisits so far. A closure is correct within 0.3 m and 5 deg."},
      {"trajectories.png",
       "The log's reference trajectory (black) and each mode's estimate moved onto it by its "
       "ATE alignment: where the map bends or a loop stays open, the tracks part."},
      {"kld.png",
       "KL divergence of each marginalization's approximate clique from the exact marginal, "
       "in nats, in the order the nodes were removed (exact marginalization: 0)."},
  };
  std::vector<ReportFigure> out;
  for (const auto& [file, caption] : plots) {
    if (fs::exists(fs::path(c.out_dir) / file)) out.push_back({file, caption, 0, 0});
  }
  return out;
}

std::string GraphSize(const ModeSummary& m) {
  if (!m.nodes_final || !m.edges_final) return "";
  return std::to_string(*m.nodes_final) + " nodes, " + std::to_string(*m.edges_final) + " edges";
}

/// Map and graph figures, truth first, every one at the same display factor.
void MapFigures(const ReportContext& c, ReportPage* page) {
  const std::string scale = "1 px = " + Num(c.map_m_per_px * 100.0, "%.3g") + " cm";
  std::vector<ReportFigure> maps, graphs;
  if (fs::exists(fs::path(c.out_dir) / "truth" / "map.png")) {
    maps.push_back({"truth/map.png",
                    "Ground truth: the world's walls, doors and boxes and the true trajectory "
                    "(thin green), in the world frame every map here shares; " +
                        scale + ".",
                    0, 0});
  }
  const std::string frame = c.truth_frame
                                ? "moved into the world frame by its ATE alignment, over the "
                                  "true trajectory (thin green)"
                                : "in the mapper's frame (no ground truth)";
  for (const std::string& mode : OrderedModes(page->summary, page->mode_order)) {
    const auto map = page->maps.find(mode);
    const std::string size = GraphSize(page->summary.modes.at(mode));
    if (map != page->maps.end() && fs::exists(fs::path(c.out_dir) / map->second)) {
      maps.push_back({map->second,
                      mode +
                          ": the occupancy grid (black: hit at least as often as passed "
                          "through; grey: unknown) with the final graph (" +
                          size + "), " + frame + "; " + scale + ".",
                      0, 0});
    }
    const std::string graph = "graph_" + mode + ".png";
    if (fs::exists(fs::path(c.out_dir) / graph)) {
      graphs.push_back({graph,
                        mode + ": the final graph alone (" + size +
                            "), at the maps' scale and frame, as the seed's Fig. 6.6.",
                        0, 0});
    }
  }
  // One display factor for all, so that one metre has one length on the page too.
  int max_w = 0, max_h = 0;
  for (const ReportFigure& f : maps) {
    const auto [w, h] = PngSize((fs::path(c.out_dir) / f.path).string());
    max_w = std::max(max_w, w), max_h = std::max(max_h, h);
  }
  double factor = 1.0;
  if (max_w > 0) factor = std::min(factor, static_cast<double>(c.max_map_width_px) / max_w);
  if (max_h > 0) factor = std::min(factor, static_cast<double>(c.max_map_height_px) / max_h);
  for (std::vector<ReportFigure>* list : {&maps, &graphs}) {
    for (ReportFigure& f : *list) {
      const auto [w, h] = PngSize((fs::path(c.out_dir) / f.path).string());
      f.width_px = static_cast<int>(std::lround(w * factor));
      f.height_px = static_cast<int>(std::lround(h * factor));
    }
  }
  page->map_figures = std::move(maps);
  page->graph_figures = std::move(graphs);
  page->true_path_in_maps = c.truth_frame;
  page->maps_note =
      (c.truth_frame ? "Every map and graph covers the truth map's bounds in the world frame, "
                       "at one scale: "
                     : "Without ground truth each map keeps the mapper's frame and its own "
                       "bounds, but all share one scale: ") +
      scale + " in the files, shown here at " + Num(factor * 100.0, "%.0f") +
      " %; click a map for full size.";
}

/// A link for each file that exists.
ReportLinkGroup Links(const std::string& out_dir, const std::string& name, const std::string& dir,
                      const std::vector<const char*>& files) {
  ReportLinkGroup g{name, {}};
  for (const char* f : files) {
    const std::string rel = dir.empty() ? f : dir + "/" + f;
    if (fs::exists(fs::path(out_dir) / rel)) g.links.push_back({f, rel});
  }
  return g;
}

std::vector<ReportLinkGroup> FileLinks(const ReportContext& c, const ReportPage& page) {
  std::vector<ReportLinkGroup> out;
  ReportLinkGroup run = Links(c.out_dir, "run", "", {"config.yaml"});
  // summary.json is written right after this page and is the one link made before its
  // file exists: it is the run's main output, and a run that fails in between leaves no
  // summary.json (README), which marks the whole directory as incomplete anyway.
  run.links.insert(run.links.begin(), {"summary.json", "summary.json"});
  out.push_back(run);
  for (const std::string& mode : OrderedModes(page.summary, page.mode_order)) {
    ReportLinkGroup g = Links(c.out_dir, mode, mode,
                              {"timeline.csv", "marginalizations.csv", "sparsifications.csv",
                               "graph.g2o", "trajectory.tum", "map.pgm", "map.yaml", "map.png"});
    const ReportLinkGroup graph = Links(c.out_dir, mode, "", {("graph_" + mode + ".png").c_str()});
    g.links.insert(g.links.end(), graph.links.begin(), graph.links.end());
    if (!g.links.empty()) out.push_back(g);
  }
  ReportLinkGroup truth = Links(c.out_dir, "ground truth", "truth",
                                {"trajectory.tum", "map.pgm", "map.yaml", "map.png"});
  if (!truth.links.empty()) out.push_back(truth);
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

ReportContext MakeReportContext(const ExperimentConfig& config,
                                const std::vector<Observation>& stream,
                                const std::optional<GroundTruth>& truth,
                                const PlotConfig& plot_config) {
  ReportContext c;
  c.out_dir = config.out_dir;
  for (slam::PruningMode mode : config.modes) c.mode_order.push_back(slam::PruningModeName(mode));
  const double res = config.mapper.grid.resolution_m;  // as in ModeRunner::Finish
  c.map_m_per_px = MakeRunMapFrame(stream, truth ? &truth->walls : nullptr, res).m_per_px;
  c.truth_frame = truth.has_value();
  c.moving_average = plot_config.moving_average;
  c.log_time = plot_config.log_time;
  c.relations_path = config.relations_path.value_or("");
  return c;
}

void CompleteReportPage(const ReportContext& context, ReportPage* page) {
  page->mode_order = context.mode_order;
  page->figures = Plots(context);
  MapFigures(context, page);
  page->files = FileLinks(context, *page);
  page->reference = FindReferenceFigures(context.relations_path, page->summary.source);
  page->build = GetBuildInfo();
  std::error_code ec;
  page->working_dir = fs::current_path(ec).string();
  page->written_utc = NowUtc();
}

}  // namespace lifelong::eval
