// `lifelong score`: a system's trajectory and map scored on a simulated log or a run with a
// mode's metrics; known answers from trajectories made by hand, and bad input refused.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_lifelong.hpp"

namespace {

namespace fs = std::filesystem;
using lifelong::test::Lifelong;
using lifelong::test::Read;
using lifelong::test::Result;
const std::string kSource = LIFELONG_SOURCE_DIR;

fs::path Fresh(const std::string& name) { return lifelong::test::FreshPath("score_", name); }

struct Pose {
  double t, x, y, th;
};

// The simulated corridor_3 log and its truth files, made once for the suite.
const fs::path& SimulatedLog() {
  static const fs::path log = [] {
    const fs::path p = Fresh("corridor.clf");
    const Result r =
        Lifelong("simulate " + kSource + "/scenarios/corridor_3.yaml -o " + p.string());
    EXPECT_EQ(r.code, 0) << r.output;
    return p;
  }();
  return log;
}

std::vector<Pose> ReadTruth(const fs::path& tum) {
  std::vector<Pose> out;
  std::ifstream in(tum);
  double t, x, y, z, qx, qy, qz, qw;
  while (in >> t >> x >> y >> z >> qx >> qy >> qz >> qw) {
    out.push_back({t, x, y, 2.0 * std::atan2(qz, qw)});
  }
  return out;
}

fs::path WritePoses(const std::string& name, const std::vector<Pose>& poses) {
  const fs::path p = Fresh(name);
  std::ofstream out(p);
  out.precision(9);
  for (const Pose& q : poses) out << q.t << " " << q.x << " " << q.y << " " << q.th << "\n";
  return p;
}

TEST(ScoreCli, KnownAnswersOnASimulatedLog) {
  const fs::path log = SimulatedLog();
  const fs::path truth_tum = fs::path(log).replace_extension(".truth.tum");
  ASSERT_TRUE(fs::exists(truth_tum));
  ASSERT_TRUE(fs::exists(fs::path(log).replace_extension(".truth.walls.tsv")));
  const std::vector<Pose> truth = ReadTruth(truth_tum);
  ASSERT_GT(truth.size(), 100u);
  // The truth moved rigidly: ATE 0. The truth with every other pose 0.1 m to its left and
  // the others 0.1 m to its right: ATE 0.1 m whatever the alignment.
  std::vector<Pose> moved, zigzag;
  const double c = std::cos(0.3), s = std::sin(0.3);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const Pose& p = truth[i];
    moved.push_back({p.t, c * p.x - s * p.y + 5.0, s * p.x + c * p.y - 2.0, p.th + 0.3});
    const double side = (i % 2 == 0 ? 0.1 : -0.1);
    zigzag.push_back({p.t, p.x - side * std::sin(p.th), p.y + side * std::cos(p.th), p.th});
  }
  if (zigzag.size() % 2 == 1) zigzag.pop_back();
  const fs::path out = Fresh("known");
  const Result r = Lifelong("score --truth " + log.string() + " --trajectory " +
                            WritePoses("moved.txt", moved).string() + " --trajectory " +
                            WritePoses("zigzag.txt", zigzag).string() + " -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = nlohmann::json::parse(Read(out / "summary.json"));
  EXPECT_EQ(j["mode_order"], nlohmann::json::array({"score_moved", "score_zigzag"}));  // the stems
  EXPECT_NEAR(j["modes"]["score_moved"]["ate_rmse_m"].get<double>(), 0.0, 1e-5);
  EXPECT_EQ(j["modes"]["score_moved"]["reference_matched"].get<std::size_t>(), truth.size());
  EXPECT_NEAR(j["modes"]["score_zigzag"]["ate_rmse_m"].get<double>(), 0.1, 2e-3);
  EXPECT_FALSE(j["modes"]["score_moved"].contains("blur"));  // no map given
  EXPECT_TRUE(fs::exists(out / "report.html"));
  EXPECT_TRUE(fs::exists(out / "trajectories.png"));
}

// A mode's own files scored against its run give that mode's figures.
TEST(ScoreCli, AModesOwnFilesGiveItsFigures) {
  const fs::path run = Fresh("run");
  Result r =
      Lifelong("run " + kSource + "/scenarios/corridor_3.yaml --modes standard -o " + run.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path out = Fresh("own");
  r = Lifelong("score --truth " + run.string() + " --trajectory " +
               (run / "standard" / "trajectory.tum").string() + " --map " +
               (run / "standard" / "map.yaml").string() + " --name standard -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto a = nlohmann::json::parse(Read(run / "summary.json"))["modes"]["standard"];
  const auto b = nlohmann::json::parse(Read(out / "summary.json"))["modes"]["standard"];
  EXPECT_NEAR(b["ate_rmse_m"].get<double>(), a["ate_rmse_m"].get<double>(), 1e-6);
  // The map goes through an 8-bit PGM: blur and recall within a few percent.
  const double blur = a["blur"]["mean_cm"].get<double>();
  EXPECT_NEAR(b["blur"]["mean_cm"].get<double>(), blur, 0.03 * blur);
  EXPECT_NEAR(b["blur"]["recall"].get<double>(), a["blur"]["recall"].get<double>(), 0.01);
}

// A corrected log's own poses are the reference: the log's raw odometry scores worse than
// the poses themselves (here its two FLASER poses, paired scan by scan).
TEST(ScoreCli, ACorrectedLogIsTheReference) {
  const std::string log = kSource + "/tests/data/io/corrected.clf";
  std::ifstream in(log);
  std::vector<Pose> own;
  for (std::string line; std::getline(in, line);) {
    std::istringstream f(line);
    std::string type;
    int n = 0;
    f >> type;
    if (type != "FLASER") continue;
    f >> n;
    for (int i = 0; i < n; ++i) f >> type;
    double x, y, th, ox, oy, oth, t;
    f >> x >> y >> th >> ox >> oy >> oth >> t;
    own.push_back({t, x, y, th});
  }
  ASSERT_EQ(own.size(), 2u);
  const fs::path out = Fresh("corrected");
  const Result r = Lifelong("score --truth " + log + " --trajectory " +
                            WritePoses("own.txt", own).string() + " --name own -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("(corrected log)"), std::string::npos) << r.output;
  const auto j = nlohmann::json::parse(Read(out / "summary.json"));
  EXPECT_NEAR(j["modes"]["own"]["ate_rmse_m"].get<double>(), 0.0, 1e-6);
}

// A corrected log of a robot driving along a room's walls (41 beams, 10 m max range), in
// GMapping's pattern: each scan's raw ODOM before it, its corrected pose repeated after it.
fs::path RoomCorrectedLog() {
  std::string text;
  for (int k = 0; k < 6; ++k) {
    const double x = 0.6 * k, t = 1.0 + k;
    std::ostringstream scan;
    scan << "FLASER 41";
    for (int i = 0; i < 41; ++i) {
      const double a = -M_PI / 2 + M_PI * i / 40.0;  // walls at y = +-2 and x = 6
      const double to_side = std::abs(std::sin(a)) > 1e-9 ? 2.0 / std::abs(std::sin(a)) : 1e9;
      const double to_end = std::cos(a) > 1e-9 ? (6.0 - x) / std::cos(a) : 1e9;
      scan << " " << (i == 20 ? 10.0 : std::min({to_side, to_end, 9.0}));
    }
    std::ostringstream pose;
    pose << x << " 0 0";
    text += "ODOM " + pose.str() + " 0 0 0 " + std::to_string(t) + " h " + std::to_string(t) + "\n";
    text += scan.str() + " " + pose.str() + " " + pose.str() + " " + std::to_string(t) + " h " +
            std::to_string(t) + "\n";
    text += "ODOM " + pose.str() + " 0 0 0 0 h 0\nNEFF 5\n";
  }
  const fs::path log = Fresh("room_corrected.clf");
  std::ofstream(log) << text;
  return log;
}

// scan_cells on a corrected log: scoring a replay's own trajectory gives the replay's figures.
TEST(ScoreCli, ScanCellsOnACorrectedLogMatchTheReplay) {
  const fs::path log = RoomCorrectedLog();
  const fs::path run = Fresh("room_replay");
  Result r = Lifelong("replay " + log.string() + " --modes standard -o " + run.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path out = Fresh("room_score");
  r = Lifelong("score --truth " + log.string() + " --trajectory " +
               (run / "standard" / "trajectory.tum").string() + " --name standard -o " +
               out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto a = nlohmann::json::parse(Read(run / "summary.json"))["modes"]["standard"];
  const auto b = nlohmann::json::parse(Read(out / "summary.json"))["modes"]["standard"];
  ASSERT_TRUE(a.contains("scan_cells")) << a.dump();
  EXPECT_GT(a["scan_cells_reference"].get<int>(), 100);
  EXPECT_EQ(b["scan_cells"], a["scan_cells"]);
  EXPECT_EQ(b["scan_cells_reference"], a["scan_cells_reference"]);
}

TEST(ScoreCli, BadInputIsRefusedNamingIt) {
  const fs::path log = SimulatedLog();
  const fs::path tum = fs::path(log).replace_extension(".truth.tum");
  Result r = Lifelong("score --truth " + Fresh("nowhere").string() + " --trajectory " +
                      tum.string() + " -o " + Fresh("x").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("no such file"), std::string::npos) << r.output;
  r = Lifelong("score --truth " + log.string() + " --trajectory " + tum.string() + " --map " +
               kSource + "/nothing.yaml --map " + kSource + "/nothing.yaml -o " +
               Fresh("y").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("2 maps for 1 trajectories"), std::string::npos) << r.output;
  r = Lifelong("score --truth " + log.string() + " --trajectory " + tum.string() +
               " --trajectory " + tum.string() + " -o " + Fresh("z").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("names two systems"), std::string::npos) << r.output;
  // Another clock: nothing pairs.
  const fs::path late = WritePoses("late.txt", {{1e6, 0, 0, 0}, {1e6 + 1, 1, 0, 0}});
  const fs::path none = Fresh("w");
  r = Lifelong("score --truth " + log.string() + " --trajectory " + late.string() + " -o " +
               none.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("pairs with the truth"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(none));  // nothing written
}

// With the scenario that made a simulated log, a mode's own map and trajectory scored on the
// log give the run's change_recall, and each object's verdict and shares, to the digit the
// 8-bit PGM keeps. The scenario of another world, or one given with a run's directory as the
// truth, is refused naming it.
TEST(ScoreCli, TheScenarioOfASimulatedLogGivesTheRunsChangeRecall) {
  const std::string scenario = kSource + "/scenarios/changing_corridor_10min.yaml";
  const fs::path log = Fresh("changing.clf"), run = Fresh("changing_run");
  Result r = Lifelong("simulate " + scenario + " -o " + log.string());
  ASSERT_EQ(r.code, 0) << r.output;
  r = Lifelong("run " + scenario + " --modes pruned-dpg -o " + run.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string system = " --trajectory " + (run / "pruned-dpg" / "trajectory.tum").string() +
                             " --map " + (run / "pruned-dpg" / "map.yaml").string() + " --name d";
  const fs::path out = Fresh("changing_scored");
  r = Lifelong("score --truth " + log.string() + " --scenario " + scenario + system + " -o " +
               out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto a = nlohmann::json::parse(Read(run / "summary.json"))["modes"]["pruned-dpg"];
  const auto b = nlohmann::json::parse(Read(out / "summary.json"))["modes"]["d"];
  ASSERT_TRUE(b.contains("change_recall")) << b;
  EXPECT_EQ(b["change_recall"], a["change_recall"]);
  EXPECT_EQ(b["change_recall_seen"], a["change_recall_seen"]);
  ASSERT_EQ(b["changes"].size(), a["changes"].size());
  for (const auto& [name, object] : a["changes"].items()) {
    EXPECT_EQ(b["changes"][name]["shows_present"], object["shows_present"]) << name;
    EXPECT_EQ(b["changes"][name]["since_seen_s"], object["since_seen_s"]) << name;
  }
  EXPECT_TRUE(b.contains("stale_seen_cells")) << b;

  const fs::path other = Fresh("other");
  r = Lifelong("score --truth " + log.string() + " --scenario " + kSource +
               "/scenarios/corridor_3.yaml" + system + " -o " + other.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("corridor_3.yaml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not those of"), std::string::npos) << r.output;
  r = Lifelong("score --truth " + run.string() + " --scenario " + scenario + system + " -o " +
               Fresh("run_truth").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("needs a simulated log"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(other));  // nothing written
  // A simulated log without its walls file: refused, not read past.
  const fs::path bare = Fresh("bare.clf");
  fs::copy_file(log, bare);
  fs::copy_file(fs::path(log).replace_extension(".truth.tum"),
                fs::path(bare).replace_extension(".truth.tum"));
  r = Lifelong("score --truth " + bare.string() + " --scenario " + scenario + system + " -o " +
               Fresh("bare").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("truth.walls.tsv"), std::string::npos) << r.output;
}

}  // namespace
