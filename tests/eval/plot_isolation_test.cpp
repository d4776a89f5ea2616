// One failed figure never takes the others down (eval/figures/plots.hpp,
// eval/common/gnuplot_run.hpp): a run without loop closures still draws its loop chart, a broken
// figure is the only one lost and is named with its log, and messages name the directory the output
// ends up in.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "eval/figures/plots.hpp"
#include "io/atomic_file.hpp"
#include "test_files.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

const char* const kRunFigures[] = {
    "time_per_obs.png",    "nodes.png",       "edges.png",       "gamma.png", "memory.png",
    "cumulative_time.png", "performance.png", "edges_gamma.png", "kld.png",   "loop_closing.png"};

std::vector<TimelineRow> Timeline(int n, int growth) {
  std::vector<TimelineRow> rows(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    rows[i].obs = i, rows[i].time_ms = 1.0 + 0.01 * growth * i, rows[i].nodes = 1 + i * growth / 10;
    rows[i].edges = rows[i].nodes * 2, rows[i].gamma = 0.5 / (1 + i);
    rows[i].rss_mb = 100.0 + i, rows[i].graph_bytes = 1000u * static_cast<unsigned>(rows[i].nodes);
  }
  return rows;
}

/// A loop curve of a run that never closed a loop: no closure accepted, `revisits` so far.
std::vector<LoopCurvePoint> NoClosures(int revisits) {
  std::vector<LoopCurvePoint> curve;
  for (int i = 0; i < 20; ++i) curve.push_back({1.0 * i, 0.0, 0.0, 0, revisits * i / 19});
  return curve;
}

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A run with no loop closure, and one with neither closure nor revisit: every figure is
// drawn, the loop chart empty and labelled (gnuplot refused it: "all points y value
// undefined", and took every other figure with it).
TEST(PlotIsolationTest, ARunWithoutClosuresGivesEveryFigure) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const ModeTimelines timelines{{"standard", Timeline(50, 10)}, {"pruned", Timeline(50, 3)}};
  const std::map<std::string, std::vector<double>> kl{{"pruned", {0.1, 0.3}}};
  for (int revisits : {0, 5}) {
    const fs::path dir = FreshDir("lifelong_plot_no_closures");
    const std::map<std::string, std::vector<LoopCurvePoint>> curves{
        {"standard", NoClosures(revisits)}, {"pruned", NoClosures(revisits)}};
    const PlotResult r = PlotRun(timelines, kl, curves, dir.string());
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_TRUE(r.failed.empty());
    EXPECT_EQ(r.files.size(), 10u);
    for (const char* name : kRunFigures)
      EXPECT_FALSE(cv::imread((dir / name).string()).empty()) << name << ", revisits " << revisits;
    const std::string script = ReadFileText(dir / "plot_data" / "loop_closing.gp");
    EXPECT_NE(script.find("'no closures'"), std::string::npos) << script;
    EXPECT_NE(script.find("'standard (no closures)'"), std::string::npos) << script;
    EXPECT_EQ(script.find("'no revisits'") != std::string::npos, revisits == 0) << script;
  }
}

// One mode with closures and one without: the chart is drawn, only the latter is marked.
TEST(PlotIsolationTest, OnlyTheModeWithoutClosuresIsMarked) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const fs::path dir = FreshDir("lifelong_plot_some_closures");
  const std::map<std::string, std::vector<LoopCurvePoint>> curves{
      {"standard", NoClosures(5)}, {"pruned", {{10.0, 1.0, 0.5, 1, 2}, {20.0, 1.0, 0.6, 2, 3}}}};
  const PlotResult r = PlotRun({}, {}, curves, dir.string());
  EXPECT_TRUE(r.ok) << r.error;
  EXPECT_FALSE(cv::imread((dir / "loop_closing.png").string()).empty());
  const std::string script = ReadFileText(dir / "plot_data" / "loop_closing.gp");
  EXPECT_NE(script.find("'standard (no closures)'"), std::string::npos) << script;
  EXPECT_EQ(script.find("'pruned (no closures)'"), std::string::npos) << script;
  EXPECT_EQ(script.find("'no closures' at"), std::string::npos) << script;
}

// The loop chart is drawn against time when the stamps advance, else against the observation
// (the campus log's scans share one stamp: its chart was one vertical line at t = 0).
TEST(PlotIsolationTest, TheLoopChartFollowsObservationsWhenStampsDoNotAdvance) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  for (const bool one_stamp : {false, true}) {
    const fs::path dir = FreshDir("lifelong_plot_one_stamp");
    std::vector<LoopCurvePoint> curve;
    for (int i = 0; i < 20; ++i) {
      curve.push_back({one_stamp ? 0.0 : 1.0 * i, 1.0, 0.5, i / 2, i / 3, i});
    }
    const PlotResult r = PlotRun({}, {}, {{"pruned", curve}}, dir.string());
    EXPECT_TRUE(r.ok) << r.error;
    EXPECT_FALSE(cv::imread((dir / "loop_closing.png").string()).empty());
    const std::string script = ReadFileText(dir / "plot_data" / "loop_closing.gp");
    EXPECT_EQ(script.find("using 6:2") != std::string::npos, one_stamp) << script;
    EXPECT_EQ(script.find("using 1:2") != std::string::npos, !one_stamp) << script;
    EXPECT_EQ(script.find("'observation'") != std::string::npos, one_stamp) << script;
    const std::string data = ReadFileText(dir / "plot_data" / "loops_pruned.dat");
    const std::string last =
        std::string(one_stamp ? "\n0 " : "\n19 ") + "1.000000 0.500000 9 6 19\n";
    EXPECT_NE(data.find(last), std::string::npos) << data;
  }
}

// A figure whose data cannot be drawn (an empty KL series: "x range is invalid") is the
// only one lost; it is named, with a log that holds gnuplot's complaint, and no PNG of it
// (not even a temporary one) is left.
TEST(PlotIsolationTest, ABrokenFigureLosesOnlyItself) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const fs::path dir = FreshDir("lifelong_plot_broken");
  const ModeTimelines timelines{{"standard", Timeline(50, 10)}, {"pruned", Timeline(50, 3)}};
  const std::map<std::string, std::vector<double>> empty_kl{{"pruned", {}}};
  const std::map<std::string, std::vector<LoopCurvePoint>> curves{{"pruned", NoClosures(3)}};
  const PlotResult r = PlotRun(timelines, empty_kl, curves, dir.string());
  EXPECT_FALSE(r.ok);
  ASSERT_EQ(r.failed.size(), 1u) << r.error;
  EXPECT_EQ(r.failed[0].figure, "kld.png");
  EXPECT_EQ(r.failed[0].log, (dir / "plot_data" / "kld.log").string());
  EXPECT_NE(r.error.find("kld.png"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(r.failed[0].log), std::string::npos) << r.error;
  EXPECT_NE(ReadFileText(r.failed[0].log).find("range"), std::string::npos)
      << ReadFileText(r.failed[0].log);
  EXPECT_EQ(r.files.size(), 9u);
  for (const char* name : kRunFigures) {
    const bool lost = std::string(name) == "kld.png";
    EXPECT_EQ(cv::imread((dir / name).string()).empty(), lost) << name;
    EXPECT_FALSE(fs::exists(io::TempPathFor((dir / name).string()))) << name;
  }
  // A figure that drew leaves no log: the logs name exactly the figures lost.
  EXPECT_FALSE(fs::exists(dir / "plot_data" / "nodes.log"));
}

// A broken script (here a gnuplot stand-in that refuses one script) loses that figure
// alone, and the message names the directory the output is moved to, where the log is
// found after the move.
TEST(PlotIsolationTest, MessagesNameTheFinalDirectory) {
  if (!GnuplotAvailable("gnuplot")) GTEST_SKIP() << "gnuplot not installed";
  const fs::path staging = FreshDir("lifelong_plot_msg_staging");
  const fs::path final_dir = fs::temp_directory_path() / "lifelong_plot_msg_final";
  fs::remove_all(final_dir);
  const fs::path wrapper = fs::temp_directory_path() / "lifelong_plot_refuses_nodes";
  {
    std::ofstream script(wrapper);
    script << "#!/bin/sh\nfor a in \"$@\"; do case \"$a\" in *nodes.gp) "
              "echo 'nodes.gp refused on purpose' >&2; exit 1;; esac; done\n"
              "exec gnuplot \"$@\"\n";
  }
  fs::permissions(wrapper, fs::perms::owner_all);
  PlotConfig config;
  config.gnuplot = wrapper.string();
  config.named_dir = final_dir.string();
  const PlotResult r = PlotRun({{"standard", Timeline(50, 10)}}, {}, {}, staging.string(), config);
  ASSERT_EQ(r.failed.size(), 1u) << r.error;
  EXPECT_EQ(r.failed[0].figure, "nodes.png");
  EXPECT_EQ(r.files.size(), 7u);
  EXPECT_EQ(r.error.find(staging.string()), std::string::npos) << r.error;
  fs::rename(staging, final_dir);
  EXPECT_NE(ReadFileText(r.failed[0].log).find("refused on purpose"), std::string::npos)
      << r.failed[0].log;
  EXPECT_FALSE(fs::exists(final_dir / "nodes.png"));
  EXPECT_TRUE(fs::exists(final_dir / "edges.png"));
}

}  // namespace
}  // namespace lifelong::eval
