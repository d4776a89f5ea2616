// `replay` scores a log against a reference trajectory: a corrected log's own FLASER poses by
// default, or a file given with --reference (TUM or t x y theta); ATE, RPE at 1 m and the
// figure of both tracks.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "run_lifelong.hpp"
#include "sensor/pose2.hpp"

namespace {

namespace fs = std::filesystem;
using lifelong::test::Lifelong;
using lifelong::test::Read;
using lifelong::test::Result;
const std::string kSource = LIFELONG_SOURCE_DIR;

fs::path Fresh(const std::string& name) { return lifelong::test::FreshPath("reference_", name); }

TEST(ReferenceCli, ACorrectedLogIsScoredAgainstItsOwnPoses) {
  const fs::path out = Fresh("corrected");
  const Result r = Lifelong("replay " + kSource +
                            "/tests/data/io/corrected.clf --modes standard -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("reference: 2 poses (corrected FLASER poses)"), std::string::npos)
      << r.output;
  const auto s = nlohmann::json::parse(Read(out / "summary.json"));
  EXPECT_EQ(s["log"]["reference"], "corrected FLASER poses");
  EXPECT_EQ(s["log"]["reference_poses"], 2);
  const auto& m = s["modes"]["standard"];
  EXPECT_EQ(m["reference_matched"], 2);
  EXPECT_TRUE(m.contains("ate_rmse_m"));
  EXPECT_TRUE(fs::exists(out / "trajectories.png"));
  EXPECT_NE(Read(out / "report.html").find("trajectories.png"), std::string::npos);
  // The reference is written beside the modes' trajectories, for tools outside to score with.
  std::istringstream tum(Read(out / "reference" / "trajectory.tum"));
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(tum, line);) {
    std::istringstream fields(line);
    rows.emplace_back(std::istream_iterator<double>(fields), std::istream_iterator<double>());
  }
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[1].size(), 8u);
  EXPECT_DOUBLE_EQ(rows[0][0], 2.0);
  EXPECT_DOUBLE_EQ(rows[1][0], 4.0);
  EXPECT_NE(Read(out / "report.html").find("reference/trajectory.tum"), std::string::npos);
}

// Some corrected logs stamp every scan 0 (freiburg-campus): their own poses are paired by
// scan, not by time (by time every scan met the first pose, and ATE read 83 m).
TEST(ReferenceCli, ACorrectedLogWithoutStampsIsPairedScanByScan) {
  std::string text = Read(kSource + "/tests/data/io/corrected.clf");
  std::string zeroed;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const auto h = line.rfind(" h ");
    if (line[0] != '#' && h != std::string::npos) {
      line = line.substr(0, line.rfind(' ', h - 1)) + " 0 h 0";
    }
    zeroed += line + "\n";
  }
  const fs::path log = Fresh("zero_stamps.clf");
  std::ofstream(log) << zeroed;
  const fs::path out = Fresh("zero_out");
  const fs::path stamped_out = Fresh("stamped_out");
  ASSERT_EQ(Lifelong("replay " + log.string() + " --modes standard -o " + out.string()).code, 0);
  ASSERT_EQ(Lifelong("replay " + kSource + "/tests/data/io/corrected.clf --modes standard -o " +
                     stamped_out.string())
                .code,
            0);
  const auto zero = nlohmann::json::parse(Read(out / "summary.json"))["modes"]["standard"];
  const auto stamped =
      nlohmann::json::parse(Read(stamped_out / "summary.json"))["modes"]["standard"];
  EXPECT_EQ(zero["reference_matched"], 2);
  EXPECT_NEAR(zero["ate_rmse_m"].get<double>(), stamped["ate_rmse_m"].get<double>(), 1e-9);
  // A reference file cannot be paired with such a log by time: said, not guessed.
  const fs::path ref = Fresh("ref0.txt");
  std::ofstream(ref) << "0 0 0 0\n1 1 0 0\n";
  const Result r = Lifelong("replay " + log.string() + " --reference " + ref.string() + " -o " +
                            Fresh("zero_ref").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("share their stamps"), std::string::npos) << r.output;
}

TEST(ReferenceCli, AGivenReferenceIsUsedAndABadOneIsNamedBeforeTheLog) {
  const fs::path ref = Fresh("ref.txt");
  std::ofstream(ref) << "2.0 0 0 0\n4.0 1 0 0\n";
  const fs::path out = Fresh("given");
  Result r =
      Lifelong("replay " + kSource + "/tests/data/io/tiny.clf --modes standard --reference " +
               ref.string() + " -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto s = nlohmann::json::parse(Read(out / "summary.json"));
  EXPECT_EQ(s["log"]["reference"], ref.string());
  const fs::path bad = Fresh("bad.txt");
  std::ofstream(bad) << "0 1 2\n";
  r = Lifelong("replay " + kSource + "/tests/data/io/tiny.clf --reference " + bad.string() +
               " -o " + Fresh("bad_out").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(bad.string()), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("read "), std::string::npos) << "the log was read first\n" << r.output;
}

// On a log, closures are scored against the reference: a simulated log replayed against its
// own truth file has every closure right, as run's are against the truth, and loops.csv says
// which closure is wrong. A reference whose heading turns away over time makes the closures
// disagree with it.
TEST(ReferenceCli, ClosuresAreScoredAgainstTheReference) {
  const fs::path log = Fresh("c3.clf");
  ASSERT_EQ(Lifelong("simulate " + kSource + "/scenarios/corridor_3.yaml -o " + log.string()).code,
            0);
  const fs::path truth = log.parent_path() / (log.stem().string() + ".truth.tum");
  ASSERT_TRUE(fs::exists(truth));
  const auto replay = [&](const fs::path& reference, const std::string& name) {
    const fs::path out = Fresh(name);
    const Result r = Lifelong("replay " + log.string() + " --modes standard --reference " +
                              reference.string() + " -o " + out.string());
    EXPECT_EQ(r.code, 0) << r.output;
    return out;
  };
  const fs::path ran = Fresh("c3_run");
  ASSERT_EQ(
      Lifelong("run " + kSource + "/scenarios/corridor_3.yaml --modes standard -o " + ran.string())
          .code,
      0);
  const auto by_run = nlohmann::json::parse(Read(ran / "summary.json"))["modes"]["standard"];
  const fs::path out = replay(truth, "c3_true");
  const auto m = nlohmann::json::parse(Read(out / "summary.json"))["modes"]["standard"];
  ASSERT_TRUE(m.contains("loop_precision")) << m.dump();
  // The log keeps ranges to the millimetre, so the replay's closures are not run's to the
  // closure (53 against 45 accepted at 2026-12-05); scored against the truth, each is right.
  EXPECT_DOUBLE_EQ(by_run["loop_precision"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(m["loop_precision"].get<double>(), 1.0);
  EXPECT_GT(m["loop_recall"].get<double>(), 0.0);
  std::istringstream rows(Read(out / "standard" / "loops.csv"));
  std::string row;
  std::getline(rows, row);  // header
  int scored = 0;
  while (std::getline(rows, row)) scored += row.find(",0,1,") != std::string::npos ? 1 : 0;
  EXPECT_GT(scored, 5);

  // The same reference, turned by 0.01 rad per second about its start.
  std::istringstream in(Read(truth));
  const fs::path bent_path = Fresh("bent.tum");
  std::ofstream bent(bent_path);
  double t, x, y, z, qx, qy, qz, qw;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream(line) >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
    const double a = 0.01 * t, theta = 2.0 * std::atan2(qz, qw) + a;
    bent << t << ' ' << std::cos(a) * x - std::sin(a) * y << ' '
         << std::sin(a) * x + std::cos(a) * y << ' ' << theta << '\n';
  }
  bent.close();
  const auto b = nlohmann::json::parse(
      Read(replay(bent_path, "c3_bent") / "summary.json"))["modes"]["standard"];
  EXPECT_LT(b["loop_precision"].get<double>(), 0.5) << b.dump();
}

// A GMapping-corrected log whose scans are all stamped 0 (belgioioso, csail, the campus): its
// closures are still scored against its own poses, node by node. The log is made from a
// simulated one: FLASER lines carry the true poses, the ODOM line before each scan is the
// previous true pose times the odometry's step, and the one after repeats the scan's pose
// (GMapping's pattern, io/carmen_recovery.hpp).
TEST(ReferenceCli, ClosuresOfALogStampedAllAlikeAreScored) {
  const fs::path sim = Fresh("c3s.clf");
  ASSERT_EQ(Lifelong("simulate " + kSource + "/scenarios/corridor_3.yaml -o " + sim.string()).code,
            0);
  std::istringstream in(Read(sim));
  std::ostringstream log;
  log << std::setprecision(10);
  std::vector<std::string> ranges;
  lifelong::Pose2 last_true, last_odom;
  bool first = true;
  for (std::string line; std::getline(in, line);) {
    std::istringstream f(line);
    std::string type;
    f >> type;
    if (type == "ROBOTLASER1") {
      std::string skip;
      for (int i = 0; i < 7; ++i) f >> skip;
      int n = 0;
      f >> n;
      ranges.assign(static_cast<std::size_t>(n), "");
      for (std::string& r : ranges) f >> r;
    } else if (type == "TRUEPOS" && !ranges.empty()) {
      lifelong::Pose2 t, o;
      f >> t.x >> t.y >> t.theta >> o.x >> o.y >> o.theta;
      const lifelong::Pose2 odom = first ? o : last_true * lifelong::Between(last_odom, o);
      log << "ODOM " << odom.x << ' ' << odom.y << ' ' << odom.theta << " 0 0 0 0 h 0\n";
      log << "FLASER " << ranges.size();
      for (const std::string& r : ranges) log << ' ' << r;
      for (int k = 0; k < 2; ++k) log << ' ' << t.x << ' ' << t.y << ' ' << t.theta;
      log << " 0 h 0\n";
      log << "ODOM " << t.x << ' ' << t.y << ' ' << t.theta << " 0 0 0 0 h 0\n";
      last_true = t;
      last_odom = o;
      first = false;
      ranges.clear();
    }
  }
  const fs::path corrected = Fresh("c3s-corrected.clf");
  std::ofstream(corrected) << log.str();
  const fs::path out = Fresh("c3s_out");
  const Result r =
      Lifelong("replay " + corrected.string() + " --modes standard -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("corrected FLASER poses"), std::string::npos) << r.output;
  // The trajectory files carry the stamps as they are; the user is told to pair by line.
  EXPECT_NE(r.output.find("share their stamps (1 distinct of"), std::string::npos) << r.output;
  const auto summary = nlohmann::json::parse(Read(out / "summary.json"));
  EXPECT_EQ(summary["log"]["distinct_stamps"].get<int>(), 1) << summary["log"].dump();
  const auto& m = summary["modes"]["standard"];
  ASSERT_TRUE(m.contains("loop_precision")) << m.dump();
  EXPECT_GT(m["loop_verification"]["accepted"].get<int>(), 5) << m.dump();
  EXPECT_GT(m["loop_precision"].get<double>(), 0.9) << m.dump();
}

}  // namespace
