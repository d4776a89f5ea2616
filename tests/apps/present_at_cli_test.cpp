// `lifelong run --present-at`: the map of the present scored at times the user gives, in
// summary.json beside the end's figures; a time after the run's end is said and skipped, and
// a time that is no positive number is refused.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "run_lifelong.hpp"

namespace {

using lifelong::test::Lifelong;
using lifelong::test::Read;
using lifelong::test::Result;
const std::string kSource = LIFELONG_SOURCE_DIR;

TEST(PresentAtCli, ScoresTheMapOfThePresentAtTheGivenTimes) {
  const auto out = lifelong::test::FreshPath("present_at_", "run");
  const Result r = Lifelong("run " + kSource +
                            "/scenarios/changing_corridor_10min.yaml --modes pruned "
                            "--present-at 400,120,9000 -o " +
                            out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("--present-at 9000 s is after the run's end"), std::string::npos)
      << r.output;
  const auto summary = nlohmann::json::parse(Read(out / "summary.json"));
  const auto& list = summary["modes"]["pruned"]["present_at"];
  ASSERT_EQ(list.size(), 2u) << list;
  EXPECT_EQ(list[0]["t_s"], 120.0);  // in time order
  EXPECT_EQ(list[1]["t_s"], 400.0);
  for (const auto& p : list) {
    EXPECT_GT(p["current_blur_cm"].get<double>(), 0.5) << p;
    EXPECT_LT(p["current_blur_cm"].get<double>(), 6.0) << p;
    EXPECT_GT(p["current_recall"].get<double>(), 0.3) << p;
    EXPECT_LT(p["ate_rmse_m"].get<double>(), 0.1) << p;
    EXPECT_TRUE(p.contains("stale_cells")) << p;
  }
  // Doors flip before 400 s: the change recall then counts the objects seen by then.
  EXPECT_TRUE(list[1].contains("change_recall_seen")) << list[1];
  // Its stale cells seen gone are some of its stale cells.
  ASSERT_TRUE(list[1].contains("stale_seen_cells")) << list[1];
  EXPECT_LE(list[1]["stale_seen_cells"].get<double>(), list[1]["stale_cells"].get<double>());

  const Result bad = Lifelong("run " + kSource + "/scenarios/corridor_3.yaml --present-at -5 -o " +
                              lifelong::test::FreshPath("present_at_", "bad").string());
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--present-at"), std::string::npos) << bad.output;
}

}  // namespace
