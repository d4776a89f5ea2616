// The order and the banners of report.html (eval/report/report_html.hpp, report_alerts.hpp,
// report_files.hpp): charts and maps first, then the key figures with the full table
// folded below; a figure gnuplot failed on is named with its log; a page without charts
// says why; a relations replay that used few relations of its file, and a simulation that
// collided or timed out, say so in red.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "eval/figures/draw.hpp"
#include "eval/report/report_files.hpp"
#include "eval/report/report_html.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

ReportPage Page() {
  ReportPage page;
  page.summary.source = "x.yaml";
  page.summary.modes["standard"].observations = 4;
  page.summary.modes["standard"].nodes_final = 4;
  page.summary.modes["pruned"].observations = 4;
  page.summary.modes["pruned"].nodes_final = 2;
  page.summary.mode_order = {"standard", "pruned"};
  page.lead_figures = {{"time_per_obs.png", "Time.", 0, 0}, {"nodes.png", "Nodes.", 0, 0}};
  page.figures = {{"memory.png", "Memory.", 0, 0}};
  page.map_cards = {{"ground truth", "", {{"truth/map.png", "Truth.", 450, 150}}}};
  return page;
}

fs::path OutDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("lifelong_report_layout_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void Png(const fs::path& p) { WritePng(p.string(), Image{4, 3, std::vector<std::uint8_t>(36, 9)}); }

TEST(ReportLayoutTest, ChartsAndMapsLeadThenKeyFiguresThenTheFoldedTable) {
  const std::string html = ReportHtmlText(Page());
  const std::size_t time = html.find("src=\"time_per_obs.png\"");
  const std::size_t nodes = html.find("src=\"nodes.png\"");
  const std::size_t map = html.find("src=\"truth/map.png\"");
  const std::size_t key = html.find("<table class=\"summary key\">");
  const std::size_t details = html.find("<details>");
  const std::size_t full = html.find("<table class=\"summary\">");
  const std::size_t more = html.find("src=\"memory.png\"");
  for (std::size_t at : {time, nodes, map, key, details, full, more})
    ASSERT_NE(at, std::string::npos) << html;
  EXPECT_LT(time, nodes);
  EXPECT_LT(nodes, map);
  EXPECT_LT(map, key);
  EXPECT_LT(key, details);
  EXPECT_LT(details, full);
  EXPECT_LT(full, html.find("</details>"));  // the full table is folded
  EXPECT_LT(html.find("</details>"), more);
}

// gnuplot failed on kld.png only: the page names it with its log, the rest is shown.
TEST(ReportLayoutTest, AFailedFigureIsNamedWithItsLog) {
  const fs::path dir = OutDir("failed");
  fs::create_directories(dir / "plot_data");
  Png(dir / "nodes.png");
  std::ofstream(dir / "plot_data" / "kld.log") << "x range is invalid\n";
  ReportPage page = Page();
  ReportContext c;
  c.out_dir = dir.string();
  c.files = {"nodes.png"};
  c.failed_plots = {"kld.png"};
  c.gnuplot_ran = true;
  CompleteReportPage(c, &page);
  ASSERT_EQ(page.failed_figures.size(), 1u);
  EXPECT_EQ(page.failed_figures[0].label, "kld.png");
  EXPECT_EQ(page.failed_figures[0].path, "plot_data/kld.log");
  ASSERT_EQ(page.lead_figures.size(), 1u);
  EXPECT_TRUE(page.figures_note.empty());
  const std::string html = ReportHtmlText(page);
  EXPECT_NE(html.find("<div class=\"notice\"><b>Figures not drawn:</b> kld.png"), std::string::npos)
      << html;
  EXPECT_NE(html.find("<a href=\"plot_data/kld.log\">"), std::string::npos);
}

// No chart at all: the section says why instead of standing empty.
TEST(ReportLayoutTest, APageWithoutChartsSaysWhy) {
  const fs::path dir = OutDir("none");
  ReportContext c;
  c.out_dir = dir.string();
  ReportPage page = Page();
  CompleteReportPage(c, &page);
  EXPECT_TRUE(page.lead_figures.empty());
  EXPECT_NE(page.figures_note.find("gnuplot was not found"), std::string::npos);
  EXPECT_NE(ReportHtmlText(page).find(page.figures_note), std::string::npos);
  c.gnuplot_ran = true;
  ReportPage failed = Page();
  CompleteReportPage(c, &failed);
  EXPECT_NE(failed.figures_note.find("gnuplot failed"), std::string::npos);
}

// Four cards (truth and three modes) of office-like maps: one row of four, not a row of
// three and one left alone, even though three columns would show them larger.
TEST(ReportLayoutTest, MapCardsFillTheirRows) {
  const fs::path dir = OutDir("cards");
  ReportPage page = Page();
  page.summary.modes["pruned-exact"].observations = 4;
  page.summary.mode_order = {"standard", "pruned", "pruned-exact"};
  fs::create_directories(dir / "truth");
  const auto png = [&](const std::string& rel) {
    fs::create_directories((dir / rel).parent_path());
    WritePng((dir / rel).string(), Image{841, 441, std::vector<std::uint8_t>(3u * 841 * 441, 9)});
  };
  png("truth/map.png");
  ReportContext c;
  c.out_dir = dir.string();
  c.files = {"truth/map.png"};
  for (const std::string& m : page.summary.mode_order) {
    png(m + "/map.png");
    png("graph_" + m + ".png");
    page.maps[m] = m + "/map.png";
    c.files.insert({m + "/map.png", "graph_" + m + ".png"});
  }
  CompleteReportPage(c, &page);
  ASSERT_EQ(page.map_cards.size(), 4u);
  EXPECT_EQ(page.map_columns, 4);
  EXPECT_LE(4 * page.map_cards[0].figures[0].width_px + 3 * 16, c.page_width_px);
}

// 6 of 120 relations used: a red banner and "6 of 120" in the tables; 100 of 120 (more
// than half): the count with its total, no banner.
TEST(ReportLayoutTest, FewRelationsUsedAreFlagged) {
  ReportPage page = Page();
  page.summary.log = LogInfo{};
  page.summary.log->relations_in_file = 120;
  page.summary.modes["pruned"].relations = RelationsSummary{6, 0.1, 0.1, 1.0, 1.0};
  std::string html = ReportHtmlText(page);
  EXPECT_NE(html.find("<div class=\"alert\"><b>Few relations used.</b> Of the 120 relations"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("(pruned 6)"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"warn\">6 of 120</td>"), std::string::npos);
  page.summary.modes["pruned"].relations->count = 100;
  html = ReportHtmlText(page);
  EXPECT_EQ(html.find("class=\"alert\""), std::string::npos);
  EXPECT_NE(html.find("<td>100 of 120</td>"), std::string::npos);
}

// A robot that collided or timed out did not drive its route: a red banner first, with the
// first collision and the simulated against the expected duration. Collisions the
// scenario expects are an amber note; a clean run has no banner.
TEST(ReportLayoutTest, AFailedSimulationIsARedBannerFirst) {
  ReportPage page = Page();
  page.summary.simulation = SimulationOutcome{};
  EXPECT_EQ(ReportHtmlText(page).find("class=\"alert\""), std::string::npos);
  SimulationOutcome& o = *page.summary.simulation;
  o.collided = true, o.collisions = 3, o.first_collision_s = 12.34;
  o.first_collision_with = "door lab_a", o.duration_s = 60.0, o.expected_duration_s = 240.0;
  std::string html = ReportHtmlText(page);
  const std::size_t alert = html.find("<div class=\"alert\"><b>The simulation failed:</b>");
  ASSERT_NE(alert, std::string::npos) << html;
  EXPECT_LT(alert, html.find("src=\"time_per_obs.png\""));
  EXPECT_NE(html.find("the robot collided (3 collisions; the first at 12.3 s, with <b>door "
                      "lab_a</b>); simulated 60.0 s of the expected 240.0 s"),
            std::string::npos)
      << html;
  o.collided = false, o.timed_out = true;
  html = ReportHtmlText(page);
  EXPECT_NE(html.find("failed:</b> the route timed out; simulated 60.0 s"), std::string::npos);
  o.timed_out = false, o.collided = true, o.collisions_expected = true;
  html = ReportHtmlText(page);
  EXPECT_EQ(html.find("class=\"alert\""), std::string::npos);
  EXPECT_NE(html.find("<div class=\"notice\">Collisions the scenario expects"), std::string::npos);
}

}  // namespace
}  // namespace lifelong::eval
