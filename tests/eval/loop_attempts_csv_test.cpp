// loop_attempts.csv: one row per loop search, with the refusal named as in summary.json.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "eval/experiment/mode_csv.hpp"
#include "test_files.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

TEST(LoopAttemptsCsv, OneRowPerSearchWithItsOutcome) {
  slam::LoopAttempt refused;
  refused.current = 40;
  refused.old = 3;
  refused.measured.score = 0.25;
  refused.measured.ambiguity = 0.0;  // no rival
  refused.candidates = 2;
  refused.window_m = 0.5;
  refused.window_rad = 0.15;
  refused.refused = slam::MatchRefusal::kLowScore;
  slam::LoopAttempt proposed;
  proposed.search = slam::LoopAttempt::Search::kGlobal;
  proposed.current = 41;
  proposed.old = 7;
  proposed.measured.score = 0.8125;
  proposed.measured.ambiguity = 0.75;
  proposed.candidates = 3;
  proposed.window_m = 4.0;
  proposed.window_rad = 0.2;
  proposed.proposed = true;
  proposed.accepted = 2;
  slam::LoopAttempt few;  // no match ran: no candidate matched, no score
  few.current = 42;
  few.candidates = 1;
  few.refused = slam::MatchRefusal::kFewPoints;

  const fs::path path = fs::temp_directory_path() / "lifelong_loop_attempts_test.csv";
  WriteLoopAttempts(path.string(), {{40, refused}, {41, proposed}, {42, few}});
  EXPECT_EQ(ReadFileText(path),
            "obs,node,search,candidates,old,window_m,window_rad,score,outcome,accepted,ambiguity\n"
            "40,40,local,2,3,0.5000,0.15000,0.2500,low_score,0,0.0000\n"
            "41,41,global,3,7,4.0000,0.20000,0.8125,proposed,2,0.7500\n"
            "42,42,local,1,-1,0.0000,0.00000,,few_points,0,\n");
  fs::remove(path);
}

TEST(LoopAttemptsCsv, RefusalsAreNamedAsInTheSummary) {
  EXPECT_STREQ(slam::MatchRefusalName(slam::MatchRefusal::kFewPoints), "few_points");
  EXPECT_STREQ(slam::MatchRefusalName(slam::MatchRefusal::kLowScore), "low_score");
  EXPECT_STREQ(slam::MatchRefusalName(slam::MatchRefusal::kAmbiguous), "ambiguous");
  EXPECT_STREQ(slam::MatchRefusalName(slam::MatchRefusal::kNotUnique), "not_unique");
  EXPECT_STREQ(slam::MatchRefusalName(slam::MatchRefusal::kImplausible), "implausible");
}

}  // namespace
}  // namespace lifelong::eval
