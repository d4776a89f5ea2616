// Mapper time by stage (issue #15): the totals of summary.json's stage_ms, the remainder
// as "other", and the timeline's columns.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "eval/metrics/summary.hpp"

namespace lifelong::eval {
namespace {

TimelineRow Row(double time, double match, double loop, double backend, double map, double gain,
                double marg) {
  TimelineRow r;
  r.time_ms = time;
  r.stages.match_ms = match;
  r.stages.loop_ms = loop;
  r.stages.backend_ms = backend;
  r.stages.map_update_ms = map;
  r.stages.gain_ms = gain;
  r.stages.marginalize_ms = marg;
  return r;
}

TEST(StageTimes, TotalsAndTheRemainderAsOther) {
  const auto t = StageTotals({Row(10, 4, 2, 1, 1, 1, 0.5), Row(6, 3, 1, 0, 0, 1, 0)});
  EXPECT_DOUBLE_EQ(t.at("matching"), 7.0);
  EXPECT_DOUBLE_EQ(t.at("loop_closing"), 3.0);
  EXPECT_DOUBLE_EQ(t.at("optimization"), 1.0);
  EXPECT_DOUBLE_EQ(t.at("map_update"), 1.0);
  EXPECT_DOUBLE_EQ(t.at("gains"), 2.0);
  EXPECT_DOUBLE_EQ(t.at("marginalization"), 0.5);
  EXPECT_DOUBLE_EQ(t.at("other"), 1.5);  // 16 ms in all
}

TEST(StageTimes, SummaryAndTimelineCarryThem) {
  const std::vector<TimelineRow> rows{Row(10, 4, 2, 1, 1, 1, 0.5)};
  RunSummary s;
  s.modes["pruned"] = SummarizeTimeline(rows, std::nullopt);
  const auto j = nlohmann::json::parse(SummaryJsonText(s))["modes"]["pruned"]["stage_ms"];
  EXPECT_DOUBLE_EQ(j["matching"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(j["other"].get<double>(), 0.5);
  const std::string path = ::testing::TempDir() + "stage_times_timeline.csv";
  WriteTimelineCsv(path, rows);
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  EXPECT_NE(header.find(",match_ms,loop_ms,backend_ms,map_update_ms,gain_ms,marginalize_ms"),
            std::string::npos)
      << header;
  EXPECT_NE(line.find(",4,2,1,1,1,0.5"), std::string::npos) << line;
}

}  // namespace
}  // namespace lifelong::eval
