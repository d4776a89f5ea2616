// The report's summary table (eval/report/report_table.hpp): grouped rows with units and
// definitions, modes in run order, ratios to the first mode where they mean something,
// and no row or group that no mode has.
#include "eval/report/report_table.hpp"
#include "eval/common/mode_order.hpp"

#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace lifelong::eval {
namespace {

RunSummary TwoModes() {
  RunSummary s;
  s.source = "x.yaml";
  ModeSummary standard;
  standard.observations = 249;
  standard.nodes_final = 249;
  standard.scans_kept_pct = 100.0;
  standard.time_per_obs_ms = TimeStats{4.0, 4.0, 8.0, 20.0, std::nullopt, 5.0};
  standard.ate_rmse_m = 0.02;
  ModeSummary pruned = standard;
  pruned.nodes_final = 18;
  pruned.scans_kept_pct = 7.2;
  pruned.time_per_obs_ms->mean = 1.0;
  pruned.kld = KldSummary{3, 0.25, 0.5};
  s.modes["standard"] = standard;
  s.modes["pruned"] = pruned;
  return s;
}

RunSummary InOrder(RunSummary s, std::vector<std::string> order) {
  s.mode_order = std::move(order);
  return s;
}

/// The <tr> of the row whose first cell is `label`.
std::string RowOf(const std::string& html, const std::string& label) {
  const std::size_t at = html.find("<tr><td>" + label + "</td>");
  if (at == std::string::npos) return "";
  return html.substr(at, html.find("</tr>", at) - at);
}

TEST(ReportTableTest, GroupsWithUnitsDefinitionsAndRatiosToTheFirstMode) {
  const std::string html = SummaryTableHtml(InOrder(TwoModes(), {"standard", "pruned"}));
  const std::size_t runtime = html.find(">Runtime<"), graph = html.find(">Graph and memory<");
  const std::size_t accuracy = html.find(">Accuracy<");
  ASSERT_NE(runtime, std::string::npos);
  ASSERT_NE(graph, std::string::npos);
  ASSERT_NE(accuracy, std::string::npos);
  EXPECT_LT(runtime, graph);
  EXPECT_LT(graph, accuracy);
  // Columns in run order: the baseline first.
  EXPECT_LT(html.find("standard</th>"), html.find("pruned</th>"));
  const std::string nodes = RowOf(html, "nodes, final");
  EXPECT_NE(nodes.find("<td>249</td>"), std::string::npos) << nodes;  // baseline: no ratio
  EXPECT_NE(nodes.find("18 <span class=\"ratio\">0.072\u00d7</span>"), std::string::npos) << nodes;
  EXPECT_NE(nodes.find("graph nodes at the end"), std::string::npos);  // definition
  const std::string mean = RowOf(html, "time per observation, mean");
  EXPECT_NE(mean.find("<td class=\"unit\">ms</td>"), std::string::npos) << mean;
  EXPECT_NE(mean.find("0.25\u00d7"), std::string::npos) << mean;
  EXPECT_NE(RowOf(html, "ATE RMSE").find("<td class=\"unit\">cm</td><td>2</td>"),
            std::string::npos);  // m shown as cm
  // A share has no ratio; a row one mode lacks shows a dash there.
  EXPECT_EQ(RowOf(html, "scans kept").find("ratio"), std::string::npos);
  const std::string kl = RowOf(html, "KL divergence, mean");
  EXPECT_NE(kl.find("<td class=\"na\">&ndash;</td><td>0.25</td>"), std::string::npos) << kl;
  EXPECT_NE(html.find("<b>standard</b> (the first mode of"), std::string::npos);
}

TEST(ReportTableTest, TheBaselineIsWhicheverModeRanFirst) {
  const std::string html = SummaryTableHtml(InOrder(TwoModes(), {"pruned", "standard"}));
  EXPECT_LT(html.find("pruned</th>"), html.find("standard</th>"));
  EXPECT_NE(RowOf(html, "nodes, final").find("249 <span class=\"ratio\">14\u00d7</span>"),
            std::string::npos);
  EXPECT_NE(html.find("<b>pruned</b> (the first mode of"), std::string::npos);
}

TEST(ReportTableTest, RowsAndGroupsNoModeHasAreLeftOut) {
  const std::string html = SummaryTableHtml(InOrder(TwoModes(), {"standard", "pruned"}));
  EXPECT_EQ(html.find("relation error"), std::string::npos);
  EXPECT_EQ(html.find("blur"), std::string::npos);
  EXPECT_EQ(html.find(">Map quality<"), std::string::npos);  // no row left in the group
  EXPECT_EQ(html.find("first pass"), std::string::npos);     // absent in every mode
  EXPECT_EQ(RowOf(html, "edges, final"), "");
}

TEST(ReportTableTest, OrderedModesPutsTheRunOrderFirstThenTheRest) {
  RunSummary s = TwoModes();
  s.modes["a-new-mode"] = {};
  s.mode_order = {"pruned", "missing", "standard"};
  EXPECT_EQ(OrderedModes(s), (std::vector<std::string>{"pruned", "standard", "a-new-mode"}));
}

// The figures' legends use the same order (eval/common/mode_order.hpp): a mode named twice
// is listed once, and a data file of a mode the run does not name comes last.
TEST(ReportTableTest, ModesInOrderListsEachModeOnceRunOrderFirst) {
  const std::map<std::string, std::string> files{
      {"a-new-mode", "a.dat"}, {"pruned", "p.dat"}, {"standard", "s.dat"}};
  EXPECT_EQ(ModesInOrder(files, {"standard", "pruned", "standard", "gone"}),
            (std::vector<std::string>{"standard", "pruned", "a-new-mode"}));
}

// Every figure summary.json can hold has a row with a group and a definition.
TEST(ReportTableTest, EveryContractFigureHasADefinedRow) {
  ModeSummary full = TwoModes().modes["pruned"];
  full.time_per_obs_ms->first_pass_mean = 1.0;
  full.wall_time_s = 1.0, full.edges_final = 1, full.nodes_max = 1, full.edges_max = 1;
  full.nodes_after_first_pass = 1, full.gamma_final = 0.1, full.peak_rss_mb = 1.0;
  full.graph_bytes_final = 1, full.loop_precision = 1.0, full.loop_recall = 1.0;
  full.blur = BlurSummary{1.0, 2.0, 3.0, 0.5};
  full.relations = RelationsSummary{1, 0.1, 0.1, 1.0, 1.0};
  full.map_entropy_bits = 1.0, full.occupied_share = 0.1;
  full.rpe_1m = RpeSummary{10, 0.05, 1.0};
  full.reference_matched = 11;
  full.sequential = SequentialSummary{9, 8};
  full.edges_by_kind = {
      {"odometry", 1}, {"loop", 1}, {"marginal", 1}, {"prior", 1}, {"clique_pairs", 1}};
  RunSummary s;
  s.modes["m"] = full;
  const nlohmann::json flat = nlohmann::json::parse(SummaryJsonText(s))["modes"]["m"].flatten();
  std::set<std::string> rows;
  const std::set<std::string> groups = {"Runtime", "Graph and memory", "Accuracy", "Map quality"};
  for (const TableRow& r : SummaryTableRows()) {
    rows.insert(r.pointer);
    EXPECT_TRUE(groups.count(r.group)) << r.pointer;
    EXPECT_GT(std::string(r.definition).size(), 10u) << r.pointer;
  }
  for (const auto& [pointer, value] : flat.items()) EXPECT_TRUE(rows.count(pointer)) << pointer;
}

// A stage that never ran reads "not run", not "0"; no ratio is taken against a time under
// 1 ms (35 us of bookkeeping made "82x"), nor against a stage that did not run.
TEST(ReportTableTest, NotRunAndNoRatioAgainstATimeUnderAMillisecond) {
  RunSummary s = TwoModes();
  s.modes["standard"].stage_ms = {{"optimization", 0.0}, {"matching", 400.0}, {"other", 0.035}};
  s.modes["pruned"].stage_ms = {{"optimization", 2.0}, {"matching", 100.0}, {"other", 2.87}};
  const std::string html = SummaryTableHtml(InOrder(s, {"standard", "pruned"}));
  const std::string optimization = RowOf(html, "time in optimization");
  EXPECT_NE(optimization.find("<td class=\"na\">not run</td><td>0.002</td>"), std::string::npos)
      << optimization;
  EXPECT_EQ(RowOf(html, "time in other").find("ratio"), std::string::npos);
  EXPECT_NE(RowOf(html, "time in matching").find("0.25\u00d7"), std::string::npos);
  EXPECT_NE(html.find("<i>not run</i>"), std::string::npos);  // explained in the note
}

// Precision is undefined without an accepted closure: the cell says why.
TEST(ReportTableTest, NoPrecisionWithoutClosuresSaysSo) {
  RunSummary s = TwoModes();
  s.modes["standard"].loop_verification = LoopVerificationSummary{};
  s.modes["pruned"].loop_verification = LoopVerificationSummary{};
  s.modes["pruned"].loop_verification->counts.accepted = 3;
  s.modes["pruned"].loop_precision = 1.0;
  const std::string row =
      RowOf(SummaryTableHtml(InOrder(s, {"standard", "pruned"})), "loop-closure precision");
  EXPECT_NE(row.find("<td class=\"na\">no closures</td><td>100</td>"), std::string::npos) << row;
}

// The compact table: only key figures, in their order, definitions as tooltips.
TEST(ReportTableTest, KeyTableHoldsTheKeyFiguresOnly) {
  const std::string html = KeyTableHtml(InOrder(TwoModes(), {"standard", "pruned"}));
  EXPECT_NE(html.find("<table class=\"summary key\">"), std::string::npos);
  EXPECT_EQ(html.find("definition"), std::string::npos);
  EXPECT_LT(html.find(">time per observation, mean<"), html.find(">nodes, final<"));
  EXPECT_LT(html.find(">nodes, final<"), html.find(">ATE RMSE<"));
  EXPECT_EQ(html.find("observations<"), std::string::npos);  // not a key figure
  EXPECT_NE(html.find("title=\"mapper time per observation, mean"), std::string::npos);
  EXPECT_GE(KeyFigurePointers().size(), 8u);
  EXPECT_LE(KeyFigurePointers().size(), 13u);
  for (const std::string& pointer : KeyFigurePointers()) {
    bool defined = false;
    for (const TableRow& r : SummaryTableRows()) defined = defined || r.pointer == pointer;
    EXPECT_TRUE(defined) << pointer;
  }
}

TEST(ReportTableTest, FormatsValuesAndRatios) {
  EXPECT_EQ(FormatValue(249, true), "249");
  EXPECT_EQ(FormatValue(0.0229, false), "0.0229");
  EXPECT_EQ(FormatValue(12345.6, false), "12346");
  EXPECT_EQ(FormatValue(5.4321, false), "5.43");
  EXPECT_EQ(FormatRatio(0.25), "0.25\u00d7");
  EXPECT_EQ(FormatRatio(28.4), "28\u00d7");
  EXPECT_EQ(FormatRatio(498.0), "498\u00d7");
}

}  // namespace
}  // namespace lifelong::eval
