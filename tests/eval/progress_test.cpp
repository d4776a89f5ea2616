// Progress lines (eval/common/progress.hpp): rate, times real time, ETA; plain lines per 10 %
// when the output is not a terminal.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "eval/common/progress.hpp"

namespace lifelong::eval {
namespace {

int Count(const std::string& s, const std::string& what) {
  int n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(Progress, LineGivesRateRealTimeFactorAndEta) {
  ProgressMeter meter(nullptr, 1000.0, {"pruned", "obs", false});
  meter.SetElapsedForTest(10.0);
  // 250 of 1000 observations in 10 s, covering 500 s of robot time.
  const std::string line = meter.Line(250.0, 500.0, "nodes 7");
  EXPECT_NE(line.find("25.0 %"), std::string::npos) << line;
  EXPECT_NE(line.find("25.0 obs/s"), std::string::npos) << line;
  EXPECT_NE(line.find("50.0x real time"), std::string::npos) << line;
  EXPECT_NE(line.find("ETA 30 s"), std::string::npos) << line;  // 750 obs at 25 obs/s
  EXPECT_NE(line.find("nodes 7"), std::string::npos) << line;
}

// A factor too long for a fixed buffer (robot time of 1e300 s) is printed whole, and the
// line holds only what was printed: it read past its buffer before.
TEST(Progress, AnyLengthOfNumberIsPrintedWhole) {
  ProgressMeter meter(nullptr, 1000.0, {"standard", "obs", false});
  meter.SetElapsedForTest(1.0);
  const std::string line = meter.Line(100.0, 1e300, "nodes 7");
  EXPECT_EQ(line.find('\0'), std::string::npos);
  EXPECT_NE(line.find("x real time  elapsed 1 s"), std::string::npos) << line;
  EXPECT_NE(line.find("nodes 7"), std::string::npos) << line;
  EXPECT_GT(line.size(), 300u);
}

TEST(Progress, NotATerminalGivesOnePlainLinePerTenPercent) {
  std::ostringstream out;
  ProgressMeter meter(&out, 1000.0, {"standard", "obs", false});
  for (int i = 1; i <= 1000; ++i) meter.Update(i, i * 0.5);
  meter.Finish(500.0);
  const std::string s = out.str();
  EXPECT_EQ(s.find('\r'), std::string::npos);
  EXPECT_EQ(Count(s, "\n"), 10);
  EXPECT_NE(s.find("10.0 %"), std::string::npos);
  EXPECT_NE(s.find("100.0 %"), std::string::npos);
}

TEST(Progress, ATerminalRedrawsInOnePercentSteps) {
  std::ostringstream out;
  ProgressMeter meter(&out, 100.0, {"simulate", "sim s", true});
  for (int i = 1; i <= 100; ++i) {
    meter.Update(i - 0.5, i);  // crosses each whole percent once
    meter.Update(i, i);
  }
  meter.Finish(100.0);
  const std::string s = out.str();
  EXPECT_GE(Count(s, "\r"), 100);
  EXPECT_EQ(Count(s, "\n"), 1);  // only the end of the line
  EXPECT_NE(s.find("37.0 %"), std::string::npos);
}

TEST(Progress, FormatsDurations) {
  EXPECT_EQ(FormatDuration(12.4), "12 s");
  EXPECT_EQ(FormatDuration(247.0), "4:07");
  EXPECT_EQ(FormatDuration(3903.0), "1:05:03");
  EXPECT_EQ(FormatDuration(-1.0), "?");
}

}  // namespace
}  // namespace lifelong::eval
