// report.html (eval/report/report_html.hpp) and what it gathers from an output directory
// (eval/report/report_files.hpp): captions, full size on click, the legend in the palette's
// colours, one display scale for all maps, links only to files that exist, provenance.
// The page's order and banners: report_layout_test.cpp.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "eval/figures/draw.hpp"
#include "eval/figures/mode_colors.hpp"
#include "eval/report/report_files.hpp"
#include "eval/report/report_html.hpp"
#include "render/palette.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

std::size_t Count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

ReportPage Page() {
  ReportPage page;
  page.summary.source = "a<b>.yaml";
  page.summary.modes["standard"].observations = 4;
  page.summary.modes["pruned"].observations = 4;
  page.summary.modes["pruned"].relations = RelationsSummary{12, 0.025, 0.02, 1.0, 2.0};
  page.summary.mode_order = {"standard", "pruned"};
  page.command_line = "lifelong run x.yaml --modes standard,pruned";
  page.working_dir = "/home/me";
  page.machine = "Test CPU";
  page.build = {"0.1.0", "abc1234-dirty"};
  page.lead_figures = {{"time_per_obs.png", "Time per observation.", 0, 0}};
  page.map_cards = {{"ground truth", "", {{"truth/map.png", "Ground truth.", 450, 150}}},
                    {"standard",
                     ModeColourHex("standard"),
                     {{"standard/map.png", "standard map.", 450, 150},
                      {"graph_standard.png", "standard graph.", 450, 150}}}};
  page.true_path_in_maps = true;
  page.files = {{"standard", {{"timeline.csv", "standard/timeline.csv"}}}};
  return page;
}

TEST(ReportHtmlTest, EveryFigureHasACaptionAndOpensFullSize) {
  const std::string html = ReportHtmlText(Page());
  EXPECT_EQ(Count(html, "<figure>"), 4u);
  EXPECT_EQ(Count(html, "<figcaption>"), 4u);
  EXPECT_NE(html.find("<a href=\"standard/map.png\"><img src=\"standard/map.png\""),
            std::string::npos);
  EXPECT_NE(html.find("width=\"450\" height=\"150\""), std::string::npos);
  EXPECT_NE(html.find("<figcaption>Time per observation.</figcaption>"), std::string::npos);
  EXPECT_NE(html.find("a&lt;b&gt;.yaml"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);  // offline, no scripts
  EXPECT_EQ(html.find("http"), std::string::npos);
}

TEST(ReportHtmlTest, LegendUsesThePaletteAndModesTheirColours) {
  const std::string html = ReportHtmlText(Page());
  for (EdgeKind k : {EdgeKind::kOdometry, EdgeKind::kLoop, EdgeKind::kMarginal}) {
    EXPECT_NE(html.find("background:" + HexColour(render::EdgeColour(k))), std::string::npos);
  }
  EXPECT_NE(html.find("background:" + HexColour(render::kTrueTrajectory) + "\"></span>true"),
            std::string::npos);
  EXPECT_EQ(Count(html, "<div class=\"legend\">"), 1u);  // above the maps and graphs
  EXPECT_NE(html.find("background:" + ModeColourHex("pruned")), std::string::npos);
}

TEST(ReportHtmlTest, ProvenanceAndFiles) {
  const std::string html = ReportHtmlText(Page());
  EXPECT_NE(html.find("lifelong 0.1.0"), std::string::npos);
  EXPECT_NE(html.find("<code>abc1234-dirty</code>"), std::string::npos);
  EXPECT_NE(html.find("lifelong run x.yaml --modes standard,pruned"), std::string::npos);
  EXPECT_NE(html.find("/home/me"), std::string::npos);
  EXPECT_NE(html.find("Test CPU"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"standard/timeline.csv\">timeline.csv</a>"), std::string::npos);
}

TEST(ReportHtmlTest, PublishedFiguresBesideThisRunsWhenKnown) {
  ReportPage page = Page();
  EXPECT_EQ(ReportHtmlText(page).find("Published figures:"), std::string::npos);
  page.reference = FindReferenceFigures("intel.relations", "intel-raw.clf.gz");
  const std::string html = ReportHtmlText(page);
  EXPECT_NE(html.find("Published figures: Intel Research Lab"), std::string::npos);
  EXPECT_NE(html.find("<td>Graph mapping</td><td>0.031 &plusmn; 0.026</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>Cartographer</td><td>0.0229 &plusmn; 0.0239</td>"), std::string::npos);
  EXPECT_NE(html.find("<b>pruned</b> (this run)</td><td>0.025 &plusmn; 0.02</td>"),
            std::string::npos);
  EXPECT_NE(html.find("29 % of the scans"), std::string::npos);
}

fs::path OutDir() {
  const fs::path d = fs::temp_directory_path() / "lifelong_eval_report_files";
  fs::remove_all(d);
  for (const char* sub : {"standard", "pruned", "truth"}) fs::create_directories(d / sub);
  return d;
}

void Touch(const fs::path& p) { std::ofstream(p) << "x\n"; }

void Png(const fs::path& p, int w, int h) {
  WritePng(p.string(), Image{w, h, std::vector<std::uint8_t>(3u * w * h, 255)});
}

// The page links and shows the files the run's writers wrote, and no other file of the
// directory (a stale one left there is not the run's).
TEST(ReportFilesTest, LinksOnlyFilesTheRunWroteAndPlotsInTheSeedsOrder) {
  const fs::path dir = OutDir();
  ReportContext c;
  c.out_dir = dir.string();
  for (const char* f : {"config.yaml", "standard/timeline.csv", "standard/graph.g2o",
                        "pruned/timeline.csv", "pruned/marginalizations.csv"}) {
    Touch(dir / f);
    c.files.insert(f);
  }
  Touch(dir / "standard" / "trajectory.tum");  // on disk, but not written by this run
  for (const char* f : {"nodes.png", "time_per_obs.png", "memory.png"}) {
    Png(dir / f, 8, 5);
    c.files.insert(f);
  }
  Png(dir / "edges.png", 8, 5);  // likewise
  c.gnuplot_ran = true;
  ReportPage page = Page();
  page.summary.mode_order = {"standard", "pruned"};
  CompleteReportPage(c, &page);
  std::vector<std::string> lead, plots;
  for (const ReportFigure& f : page.lead_figures) lead.push_back(f.path);
  for (const ReportFigure& f : page.figures) plots.push_back(f.path);
  EXPECT_EQ(lead, (std::vector<std::string>{"time_per_obs.png", "nodes.png"}));
  EXPECT_EQ(plots, (std::vector<std::string>{"memory.png"}));
  for (const ReportFigure& f : page.lead_figures) EXPECT_FALSE(f.caption.empty()) << f.path;
  for (const ReportFigure& f : page.figures) EXPECT_FALSE(f.caption.empty()) << f.path;
  EXPECT_TRUE(page.failed_figures.empty());
  EXPECT_TRUE(page.figures_note.empty());
  std::set<std::string> links;
  for (const ReportLinkGroup& g : page.files)
    for (const ReportLink& l : g.links) links.insert(l.path);
  EXPECT_EQ(links, (std::set<std::string>{"summary.json", "config.yaml", "standard/timeline.csv",
                                          "standard/graph.g2o", "pruned/timeline.csv",
                                          "pruned/marginalizations.csv"}));
  EXPECT_FALSE(page.reference.has_value());
  EXPECT_FALSE(page.build.commit.empty());
  EXPECT_FALSE(page.written_utc.empty());
}

// Each mode's map and graph share a card, the truth's first, the modes in run order; all
// images at one factor; the columns that give the largest images for the cells filled
// within the grid's height.
TEST(ReportFilesTest, MapsTruthFirstAtOneDisplayScale) {
  const fs::path dir = OutDir();
  Png(dir / "truth" / "map.png", 1800, 400);
  Png(dir / "standard" / "map.png", 1800, 400);
  Png(dir / "pruned" / "map.png", 900, 200);
  Png(dir / "graph_pruned.png", 900, 200);
  ReportPage page = Page();
  page.maps = {{"standard", "standard/map.png"}, {"pruned", "pruned/map.png"}};
  ReportContext c;
  c.out_dir = dir.string();
  c.files = {"truth/map.png", "standard/map.png", "pruned/map.png", "graph_pruned.png"};
  page.summary.mode_order = {"pruned", "standard"};
  c.truth_frame = true;
  c.page_width_px = 900;
  CompleteReportPage(c, &page);
  ASSERT_EQ(page.map_cards.size(), 3u);
  EXPECT_EQ(page.map_cards[0].name, "ground truth");
  EXPECT_EQ(page.map_cards[1].name, "pruned");  // run order
  ASSERT_EQ(page.map_cards[1].figures.size(), 2u);
  EXPECT_EQ(page.map_cards[1].figures[0].path, "pruned/map.png");
  EXPECT_EQ(page.map_cards[1].figures[1].path, "graph_pruned.png");
  EXPECT_EQ(page.map_cards[1].colour, ModeColourHex("pruned"));
  // One column fits: 1800 px shown at 900 (50 %), and every other image at 50 % too.
  EXPECT_EQ(page.map_columns, 1);
  EXPECT_EQ(page.map_cards[0].figures[0].width_px, 900);
  EXPECT_EQ(page.map_cards[0].figures[0].height_px, 200);
  EXPECT_EQ(page.map_cards[1].figures[0].width_px, 450);
  EXPECT_EQ(page.map_cards[1].figures[1].width_px, 450);
  EXPECT_TRUE(page.true_path_in_maps);
  EXPECT_NE(page.maps_note.find("shown here at 50 %"), std::string::npos) << page.maps_note;
  // A lower limit on the grid's height puts the cards side by side, smaller.
  c.max_maps_height_px = 400;
  ReportPage low = Page();
  low.maps = page.maps;
  CompleteReportPage(c, &low);
  EXPECT_GT(low.map_columns, 1);
  EXPECT_LT(low.map_cards[0].figures[0].width_px, 900 / low.map_columns + 1);
}

TEST(ReportFilesTest, PngSizeReadsTheHeader) {
  const fs::path dir = OutDir();
  Png(dir / "a.png", 17, 9);
  EXPECT_EQ(PngSize((dir / "a.png").string()), (std::pair<int, int>{17, 9}));
  Touch(dir / "b.png");
  EXPECT_EQ(PngSize((dir / "b.png").string()), (std::pair<int, int>{0, 0}));
  EXPECT_EQ(PngSize((dir / "none.png").string()), (std::pair<int, int>{0, 0}));
}

}  // namespace
}  // namespace lifelong::eval
