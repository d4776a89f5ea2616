// Map images (pixel colours at known cells, y up, cropping) and gnuplot figures.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "eval/common/resources.hpp"
#include "eval/figures/draw.hpp"
#include "eval/figures/mode_colors.hpp"
#include "eval/figures/plots.hpp"
#include "io/atomic_file.hpp"
#include "render/palette.hpp"
#include "tests/io/file_size_limit.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

// 10 x 10 cells of 0.1 m: bottom row free, cell (5, 5) occupied, the rest unknown.
OccupancyGrid SmallGrid() {
  OccupancyGrid g;
  g.width = g.height = 10;
  g.resolution_m = 0.1;
  g.p_occ.assign(100, OccupancyGrid::kUnknown);
  for (int c = 0; c < 10; ++c) g.At(c, 0) = 0.0f;
  g.At(5, 5) = 1.0f;
  return g;
}

cv::Vec3b Pixel(const Image& im, int col, int row) {
  const std::size_t i = (static_cast<std::size_t>(row) * im.width + col) * 3;
  return {im.rgb[i + 2], im.rgb[i + 1], im.rgb[i]};  // as BGR
}

DrawConfig Plain() {
  DrawConfig c;
  c.crop_to_known = false;
  c.scale_bar = false;
  return c;
}

TEST(DrawTest, FreeWhiteOccupiedBlackUnknownGreyWithYUp) {
  const Image im = RenderMap(SmallGrid(), {}, {}, Plain());
  ASSERT_EQ(im.width, 10);
  ASSERT_EQ(im.height, 10);
  EXPECT_EQ(Pixel(im, 3, 9), cv::Vec3b(255, 255, 255));  // grid row 0 is the bottom
  EXPECT_EQ(Pixel(im, 5, 4), cv::Vec3b(0, 0, 0));        // grid row 5 -> image row 4
  EXPECT_EQ(Pixel(im, 5, 5), cv::Vec3b(205, 205, 205));
}

TEST(DrawTest, CropsToKnownCellsWithMarginAndUpscales) {
  OccupancyGrid g = SmallGrid();
  std::fill(g.p_occ.begin(), g.p_occ.end(), OccupancyGrid::kUnknown);
  g.At(3, 3) = g.At(4, 4) = 0.0f;  // known box 2 x 2 cells
  DrawConfig c;
  c.margin_m = 0.1;  // one cell
  c.scale_bar = false;
  c.pixels_per_cell = 3;
  const Image im = RenderMap(g, {}, {}, c);
  EXPECT_EQ(im.width, 4 * 3);
  EXPECT_EQ(im.height, 4 * 3);
  EXPECT_EQ(Pixel(im, 1 * 3 + 1, 2 * 3 + 1), cv::Vec3b(255, 255, 255));  // cell (3,3)
}

TEST(DrawTest, TrajectoryIsDrawnInItsColourAtWorldCoordinates) {
  TrajectoryOverlay est{TrajectoryKind::kEstimate, {{0.05, 0.75, 0}, {0.95, 0.75, 0}}};
  const Image im = RenderMap(SmallGrid(), {}, {est}, Plain());
  const cv::Vec3b p = Pixel(im, 2, 2);  // y = 0.75 m -> 7.5 px from the bottom: row 2
  EXPECT_GT(p[0], 150);                 // blue dominates
  EXPECT_LT(p[2], 100);
  EXPECT_EQ(Pixel(im, 2, 6), cv::Vec3b(205, 205, 205));  // untouched
}

// Edge kinds take the one palette the video frames use too (render/palette.hpp).
TEST(DrawTest, EdgesAreDrawnInTheSharedPalette) {
  GraphOverlay graph;
  // Through pixel centres: y = 0.7375 m is 29.5 px from the bottom of 40, image row 10.
  graph.edges.push_back({0.05, 0.7375, 0.95, 0.7375, EdgeKind::kLoop});
  graph.edges.push_back({0.05, 0.2375, 0.95, 0.2375, EdgeKind::kMarginal});
  DrawConfig config = Plain();
  config.pixels_per_cell = 4;
  const Image im = RenderMap(SmallGrid(), graph, {}, config);
  for (const auto& [row, kind] :
       {std::pair{10, EdgeKind::kLoop}, std::pair{30, EdgeKind::kMarginal}}) {
    const render::Rgb c = render::EdgeColour(kind);
    const cv::Vec3b p = Pixel(im, 20, row);
    // Anti-aliased: within a tenth of full scale of the palette colour, channel by channel.
    EXPECT_NEAR(p[0], c.b, 25) << EdgeKindName(kind);
    EXPECT_NEAR(p[1], c.g, 25) << EdgeKindName(kind);
    EXPECT_NEAR(p[2], c.r, 25) << EdgeKindName(kind);
  }
}

TEST(DrawTest, WritesAReadablePngAndNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / "lifelong_eval_draw";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::vector<Segment> walls = {{0, 0, 4, 0}, {4, 0, 4, 3}};
  WriteWorldPng((dir / "world.png").string(), walls,
                {{TrajectoryKind::kTrue, {{0.5, 0.5, 0}, {3.5, 2.5, 0}}}});
  WriteMapPng((dir / "map.png").string(), SmallGrid(), {}, {});
  const cv::Mat world = cv::imread((dir / "world.png").string());
  EXPECT_EQ(world.cols, static_cast<int>(std::lround((4 + 2.0) / 0.05)) + 1);
  EXPECT_FALSE(cv::imread((dir / "map.png").string()).empty());
  EXPECT_FALSE(fs::exists(io::TempPathFor((dir / "map.png").string())));
  EXPECT_THROW(WriteMapPng("/nonexistent_dir/map.png", SmallGrid(), {}, {}), std::runtime_error);
}

TEST(DrawTest, FailedPngWriteKeepsThePreviousPng) {
  const fs::path dir = fs::temp_directory_path() / "lifelong_eval_draw_full";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path path = dir / "map.png";
  WriteMapPng(path.string(), SmallGrid(), {}, {});
  const cv::Mat before = cv::imread(path.string());
  Image noise;  // incompressible, so the PNG is larger than the limit
  noise.width = noise.height = 256;
  std::mt19937 random(7);
  for (std::size_t i = 0; i < 256u * 256u * 3u; ++i)
    noise.rgb.push_back(static_cast<std::uint8_t>(random() >> 24));
  {
    const testing::FileSizeLimit limit(8 * 1024);
    EXPECT_THROW(WritePng(path.string(), noise), std::runtime_error);
  }
  const cv::Mat after = cv::imread(path.string());
  ASSERT_EQ(after.size(), before.size());
  EXPECT_EQ(cv::norm(after, before, cv::NORM_INF), 0.0);
  EXPECT_FALSE(fs::exists(io::TempPathFor(path.string())));
}

std::vector<TimelineRow> Timeline(int n, int growth) {
  std::vector<TimelineRow> rows(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    rows[i].obs = i, rows[i].time_ms = 1.0 + 0.01 * growth * i, rows[i].nodes = 1 + i * growth / 10;
    rows[i].edges = rows[i].nodes * 2, rows[i].gamma = 0.5 / (1 + i);
    rows[i].rss_mb = 100.0 + i, rows[i].graph_bytes = 1000u * static_cast<unsigned>(rows[i].nodes);
  }
  return rows;
}

TEST(PlotsTest, WritesEveryFigureOrReportsMissingGnuplot) {
  const fs::path dir = fs::temp_directory_path() / "lifelong_eval_plots";
  fs::remove_all(dir);
  fs::create_directories(dir);
  PlotConfig missing;
  missing.gnuplot = "/nonexistent/gnuplot";
  const PlotResult none = PlotTimelines({{"standard", Timeline(50, 10)}}, dir.string(), missing);
  EXPECT_FALSE(none.ok);
  EXPECT_NE(none.error.find("gnuplot"), std::string::npos);
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const PlotResult r =
      PlotTimelines({{"standard", Timeline(50, 10)}, {"chow_liu", Timeline(50, 3)}}, dir.string());
  EXPECT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.files.size(), 8u);
  for (const char* name :
       {"time_per_obs.png", "nodes.png", "edges.png", "gamma.png", "cumulative_time.png",
        "memory.png", "performance.png", "edges_gamma.png"}) {
    EXPECT_FALSE(cv::imread((dir / name).string()).empty()) << name;
    EXPECT_FALSE(fs::exists(io::TempPathFor((dir / name).string()))) << name;
  }
  EXPECT_GT(cv::imread((dir / "memory.png").string()).rows, 500);  // two panels
  // The seed's layouts: three and two panels side by side, wider than tall.
  const cv::Mat performance = cv::imread((dir / "performance.png").string());
  EXPECT_GT(performance.cols, 2 * performance.rows);
  const cv::Mat edges_gamma = cv::imread((dir / "edges_gamma.png").string());
  EXPECT_GT(edges_gamma.cols, edges_gamma.rows);
  const PlotResult k = PlotRun({}, {{"chow_liu", {0.1, 0.3, 0.2}}}, {}, dir.string());
  EXPECT_TRUE(k.ok) << k.error;
  EXPECT_FALSE(cv::imread((dir / "kld.png").string()).empty());
}

// A run's figures come from one gnuplot process, each script still standing alone; when
// gnuplot fails on every figure (here a stand-in that exits 1, also when each figure is
// tried alone) no figure is written, not even a partial one.
TEST(PlotsTest, ARunsFiguresInOneProcessNoneWhenGnuplotAlwaysFails) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const fs::path dir = fs::temp_directory_path() / "lifelong_eval_plot_run";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const ModeTimelines timelines{{"standard", Timeline(50, 10)}, {"pruned", Timeline(50, 3)}};
  const std::map<std::string, std::vector<double>> kl{{"pruned", {0.1, 0.3}}};
  const std::map<std::string, std::vector<LoopCurvePoint>> curves{
      {"pruned", {{10.0, 1.0, 0.5, 1, 2}, {20.0, 1.0, 0.6, 2, 3}}}};
  const PlotResult r = PlotRun(timelines, kl, curves, dir.string());
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.files.size(), 10u);
  for (const char* name : {"gamma.png", "kld.png", "loop_closing.png", "memory.png"})
    EXPECT_FALSE(cv::imread((dir / name).string()).empty()) << name;
  // The loop figure's script after the memory one's: no multiplot or log axis carried over.
  fs::remove(dir / "loop_closing.png");
  const std::string alone = "cd '" + dir.string() +
                            "' && gnuplot plot_data/memory.gp plot_data/loop_closing.gp "
                            "2>/dev/null && mv loop_closing.tmp.png loop_closing.png";
  EXPECT_EQ(std::system(alone.c_str()), 0);
  EXPECT_FALSE(cv::imread((dir / "loop_closing.png").string()).empty());

  const fs::path failing = dir / "failing-gnuplot";
  {
    std::ofstream script(failing);
    // Draws one figure, then fails.
    script << "#!/bin/sh\ncase \"$1\" in -e) echo 'png pngcairo';; "
              "*) echo x > time_per_obs.tmp.png; exit 1;; esac\n";
  }
  fs::permissions(failing, fs::perms::owner_all);
  const fs::path other = dir / "other";
  fs::create_directories(other);
  PlotConfig config;
  config.gnuplot = failing.string();
  const PlotResult failed = PlotRun(timelines, kl, {}, other.string(), config);
  EXPECT_FALSE(failed.ok);
  EXPECT_NE(failed.error.find("gnuplot.log"), std::string::npos) << failed.error;
  EXPECT_TRUE(failed.files.empty());
  EXPECT_EQ(failed.failed.size(), 9u);  // eight timeline figures and kld.png
  for (const auto& entry : fs::directory_iterator(other))
    EXPECT_NE(entry.path().extension(), ".png") << entry.path();
}

/// Pixels of the image within 30 per channel of the colour.
int CountColour(const cv::Mat& img, const render::Rgb& c) {
  int n = 0;
  for (int r = 0; r < img.rows; ++r)
    for (int col = 0; col < img.cols; ++col) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, col);
      n += std::abs(p[0] - c.b) < 30 && std::abs(p[1] - c.g) < 30 && std::abs(p[2] - c.r) < 30;
    }
  return n;
}

// A mode keeps its colour whatever else ran: standard is blue alone, first or second.
TEST(PlotsTest, EachModeKeepsItsColourInEveryRun) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const fs::path dir = fs::temp_directory_path() / "lifelong_eval_plot_colours";
  const render::Rgb blue = ModeColour("standard"), red = ModeColour("pruned");
  for (const ModeTimelines& modes :
       {ModeTimelines{{"standard", Timeline(50, 10)}},
        ModeTimelines{{"standard", Timeline(50, 10)}, {"pruned", Timeline(50, 3)}},
        ModeTimelines{{"pruned", Timeline(50, 3)}, {"a-new-mode", Timeline(50, 5)}}}) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    ASSERT_TRUE(PlotTimelines(modes, dir.string()).ok);
    for (const char* name : {"nodes.png", "cumulative_time.png", "memory.png"}) {
      const cv::Mat img = cv::imread((dir / name).string());
      EXPECT_EQ(CountColour(img, blue) > 50, modes.count("standard") == 1) << name;
      EXPECT_EQ(CountColour(img, red) > 50, modes.count("pruned") == 1) << name;
    }
  }
}

// The legend lists the modes as the run gave them (baseline first), not by name.
TEST(PlotsTest, LegendFollowsTheRunsModeOrder) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const fs::path dir = fs::temp_directory_path() / "lifelong_eval_plot_order";
  fs::remove_all(dir);
  fs::create_directories(dir);
  PlotConfig config;
  config.mode_order = {"standard", "pruned"};
  const ModeTimelines modes{
      {"pruned", Timeline(50, 3)}, {"standard", Timeline(50, 10)}, {"a-new-mode", Timeline(50, 5)}};
  ASSERT_TRUE(PlotTimelines(modes, dir.string(), config).ok);
  std::ifstream in(dir / "plot_data" / "nodes.gp");
  const std::string script((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = [&](const std::string& mode) { return script.find("title '" + mode + "'"); };
  ASSERT_NE(at("standard"), std::string::npos) << script;
  EXPECT_LT(at("standard"), at("pruned"));
  EXPECT_LT(at("pruned"), at("a-new-mode"));
}

// A run is written into a staging directory and renamed: plot_data/ must still re-make its
// figures from the final place.
TEST(PlotsTest, ScriptsReMakeTheFiguresAfterTheDirectoryMoved) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const fs::path staging = fs::temp_directory_path() / "lifelong_eval_plot_staging";
  const fs::path final_dir = fs::temp_directory_path() / "lifelong_eval_plot_final";
  fs::remove_all(staging);
  fs::remove_all(final_dir);
  fs::create_directories(staging);
  ASSERT_TRUE(PlotTimelines({{"standard", Timeline(50, 10)}}, staging.string()).ok);
  fs::rename(staging, final_dir);
  fs::remove(final_dir / "nodes.png");
  const std::string cmd =
      "cd '" + final_dir.string() +
      "' && gnuplot plot_data/nodes.gp 2>/dev/null && mv nodes.tmp.png nodes.png";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_TRUE(fs::exists(final_dir / "nodes.png"));
}

TEST(ResourcesTest, RssIsPositiveAndPeakAtLeastCurrent) {
  const auto now = CurrentRssMb();
  const auto peak = PeakRssMb();
  ASSERT_TRUE(now.has_value());
  ASSERT_TRUE(peak.has_value());
  EXPECT_GT(*now, 0.0);
  EXPECT_GE(*peak, *now);
  EXPECT_FALSE(CpuModelName().empty());
}

}  // namespace
}  // namespace lifelong::eval
