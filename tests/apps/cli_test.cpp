// The `lifelong` command as a user meets it (issue #13): results all or nothing, input
// checked before any work, no zero figure that looks right, help and errors.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "run_lifelong.hpp"

namespace {

namespace fs = std::filesystem;

using lifelong::test::Lifelong;
using lifelong::test::Read;
using lifelong::test::Result;
const std::string kBin = LIFELONG_BIN;
const std::string kSource = LIFELONG_SOURCE_DIR;
const std::string kScenario = kSource + "/scenarios/corridor_3.yaml";

fs::path Fresh(const std::string& name) { return lifelong::test::FreshPath("cli_", name); }

// No DIR.partial-* is left beside DIR.
bool NoStaging(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir.parent_path())) {
    if (e.path().filename().string().rfind(dir.filename().string() + ".partial", 0) == 0) {
      return false;
    }
  }
  return true;
}

// A simulated corridor_3 log, made once per test process (CTest runs tests in parallel
// processes, so each has its own).
const fs::path& CorridorLog() {
  static const fs::path log = [] {
    const fs::path p = Fresh("log_" + std::to_string(getpid())) / "corridor_3.clf";
    fs::create_directories(p.parent_path());
    const Result r = Lifelong("simulate " + kScenario + " -o " + p.string());
    EXPECT_EQ(r.code, 0) << r.output;
    return p;
  }();
  return log;
}

// A timeline's rows: per-stage times non-negative and within the observation's time, and
// the word for how the sequential edge came about.
void ExpectTimelineRows(const fs::path& path) {
  std::ifstream csv(path);
  std::string line;
  std::getline(csv, line);
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::istringstream fields(line);
    std::string f;
    while (v.size() < 17 && std::getline(fields, f, ',')) v.push_back(std::stod(f));
    ASSERT_EQ(v.size(), 17u) << line;
    std::getline(fields, f, ',');
    EXPECT_TRUE(f == "first" || f == "matched" || f == "degenerate" || f == "weak" ||
                f == "odometry")
        << line;
    double stages = 0.0;
    for (std::size_t k = 11; k < 17; ++k) {
      EXPECT_GE(v[k], -1e-6) << line;
      stages += v[k];
    }
    EXPECT_LE(stages, v[2] + 1e-3) << line;
    ++rows;
  }
  EXPECT_GT(rows, 100);
}

TEST(Cli, ARerunWithFewerModesLeavesNothingOfTheEarlierRun) {
  const fs::path dir = Fresh("rerun");
  Result r = Lifelong("run " + kScenario + " -o " + dir.string() +
                      " --modes 'standard, pruned, pruned-exact'");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "pruned-exact" / "timeline.csv"));
  EXPECT_TRUE(fs::exists(dir / "kld.png"));
  // Loop closing over time ends at the summary's precision.
  EXPECT_TRUE(fs::exists(dir / "loop_closing.png"));
  {
    std::ifstream dat(dir / "plot_data" / "loops_standard.dat");
    std::string line, last;
    while (std::getline(dat, line)) last = line;
    std::istringstream fields(last);
    double t = 0.0, precision = 0.0;
    fields >> t >> precision;
    const auto first = nlohmann::json::parse(Read(dir / "summary.json"));
    EXPECT_NEAR(precision, first["modes"]["standard"]["loop_precision"].get<double>(), 1e-6);
    EXPECT_TRUE(fs::exists(dir / "standard" / "loop_attempts.csv"));
  }
  {  // Each closure's two nodes: a loop edge between them in the graph (standard keeps all).
    const std::string graph = Read(dir / "standard" / "graph.g2o");
    std::istringstream rows(Read(dir / "standard" / "loops.csv"));
    std::string row;
    std::getline(rows, row);
    EXPECT_NE(row.find(",final_chi2,node_current,node_old"), std::string::npos) << row;
    int closures = 0;
    while (std::getline(rows, row)) {
      const std::string old = row.substr(row.rfind(',') + 1);
      const std::string rest = row.substr(0, row.rfind(','));
      const std::string current = rest.substr(rest.rfind(',') + 1);
      EXPECT_NE(graph.find("EDGE_SE2 " + old + " " + current + " "), std::string::npos) << row;
      ++closures;
    }
    EXPECT_GT(closures, 0);
  }
  ExpectTimelineRows(dir / "pruned" / "timeline.csv");
  // The table: modes in --modes order, the baseline first, units in the headers.
  const auto standard_row = r.output.find("\nstandard (base)");
  const auto pruned_row = r.output.find("\npruned ");
  EXPECT_NE(standard_row, std::string::npos) << r.output;
  EXPECT_LT(standard_row, pruned_row);
  EXPECT_NE(r.output.find("last 10 % [ms/obs]"), std::string::npos);
  EXPECT_EQ(r.output.find('\r'), std::string::npos) << "not a terminal: no carriage returns";

  r = Lifelong("run " + kScenario + " -o " + dir.string() + " --modes standard");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "pruned"));
  EXPECT_FALSE(fs::exists(dir / "pruned-exact"));
  EXPECT_FALSE(fs::exists(dir / "kld.png"));
  EXPECT_FALSE(fs::exists(dir / "plot_data" / "kld_pruned.dat"));
  const auto summary = nlohmann::json::parse(Read(dir / "summary.json"));
  EXPECT_EQ(summary["modes"].size(), 1u);
  EXPECT_TRUE(NoStaging(dir));
}

TEST(Cli, AFailedReplayLeavesTheEarlierResultUntouched) {
  const fs::path dir = Fresh("failed");
  ASSERT_EQ(
      Lifelong("replay " + CorridorLog().string() + " --modes standard -o " + dir.string()).code,
      0);
  const std::string before = Read(dir / "summary.json");
  const fs::path bad = Fresh("bad.relations");
  std::ofstream(bad) << "1 2 0 0 0 0 0 x\n";
  const Result r = Lifelong("replay " + CorridorLog().string() + " --modes standard -o " +
                            dir.string() + " --relations " + bad.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(bad.string() + ":1"), std::string::npos) << r.output;
  EXPECT_EQ(Read(dir / "summary.json"), before);
  EXPECT_TRUE(fs::exists(dir / "report.html"));
  EXPECT_TRUE(NoStaging(dir));
}

TEST(Cli, CtrlCLeavesTheEarlierResultUntouched) {
  const fs::path dir = Fresh("interrupt");
  ASSERT_EQ(Lifelong("run " + kScenario + " --modes standard -o " + dir.string()).code, 0);
  const std::string before = Read(dir / "summary.json");
  // corridor_100 takes minutes: the signal lands mid-run. It is sent once the program
  // says it is simulating (its handler is in place by then), not after a fixed delay
  // that a loaded machine could outlast.
  int err[2];
  ASSERT_EQ(pipe(err), 0);
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(err[1], 2);
    close(err[0]);
    execl(kBin.c_str(), kBin.c_str(), "run", (kSource + "/scenarios/corridor_100.yaml").c_str(),
          "-o", dir.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(err[1]);
  std::string said;
  char buf[256];
  for (ssize_t n;
       said.find("simulating") == std::string::npos && (n = read(err[0], buf, sizeof(buf))) > 0;) {
    said.append(buf, static_cast<std::size_t>(n));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGINT);
  while (read(err[0], buf, sizeof(buf)) > 0) {
  }
  close(err[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_EQ(Read(dir / "summary.json"), before);
  EXPECT_TRUE(NoStaging(dir));
}

TEST(Cli, ADirectoryThatIsNoOutputIsNeverReplaced) {
  const fs::path dir = Fresh("foreign");
  fs::create_directories(dir);
  std::ofstream(dir / "notes.txt") << "precious";
  const Result r = Lifelong("run " + kScenario + " --modes standard -o " + dir.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(r.output.find("simulating"), std::string::npos) << "checked before any work";
  EXPECT_EQ(Read(dir / "notes.txt"), "precious");
}

TEST(Cli, SimulateChecksItsOutputBeforeSimulating) {
  const Result r = Lifelong("simulate " + kScenario + " -o /proc/no/such/dir/x.clf");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(r.output.find("simulating"), std::string::npos) << r.output;
}

TEST(Cli, RelationsThatMatchNoScanAreAnInputErrorNotAZero) {
  const fs::path rel = Fresh("offset.relations");
  // Relations between true poses of the log's scans, in a clock 1000 s ahead.
  std::vector<double> stamps;
  {
    std::ifstream in(CorridorLog().string().substr(0, CorridorLog().string().size() - 4) +
                     ".truth.tum");
    for (std::string line; std::getline(in, line);) {
      if (!line.empty() && line[0] != '#') stamps.push_back(std::stod(line));
    }
  }
  ASSERT_GT(stamps.size(), 40u);
  {
    std::ofstream out(rel);
    out.precision(17);
    for (std::size_t i = 0; i + 5 < 40; i += 5) {
      out << stamps[i] + 1000.0 << " " << stamps[i + 5] + 1000.0 << " 0 0 0 0 0 0\n";
    }
  }
  const fs::path dir = Fresh("offset");
  Result r = Lifelong("replay " + CorridorLog().string() + " --modes standard -o " + dir.string() +
                      " --relations " + rel.string() + " --relations-offset 7");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("7 relations"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(std::to_string(stamps.size()) + " scans"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir));

  // The simulator stamps scans at a regular rate, so shifts by whole periods fit as well:
  // detection must say so rather than pick one.
  r = Lifelong("replay " + CorridorLog().string() + " --modes standard -o " + dir.string() +
               " --relations " + rel.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("give --relations-offset"), std::string::npos) << r.output;

  r = Lifelong("replay " + CorridorLog().string() + " --modes standard -o " + dir.string() +
               " --relations " + rel.string() + " --relations-offset 1000");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("7 of 7"), std::string::npos) << r.output;
  const auto summary = nlohmann::json::parse(Read(dir / "summary.json"));
  EXPECT_NEAR(summary["log"]["relations_offset_s"].get<double>(), 1000.0, 1e-6);
  EXPECT_FALSE(summary["log"]["relations_offset_detected"].get<bool>());
  EXPECT_EQ(summary["modes"]["standard"]["relations"]["count"].get<int>(), 7);
}

TEST(Cli, BackwardStampsAreReportedAndTheDurationNeverNegative) {
  // The corridor log with its last scan stamped before the first.
  std::string text = Read(CorridorLog());
  const auto last = text.rfind("ROBOTLASER1");
  ASSERT_NE(last, std::string::npos);
  const auto eol = text.find('\n', last);
  std::string line = text.substr(last, eol - last);
  // ROBOTLASER1 ... ipc_timestamp host logger_timestamp: the last three fields.
  std::istringstream fields(line);
  std::vector<std::string> f;
  for (std::string w; fields >> w;) f.push_back(w);
  f[f.size() - 3] = "-50.0";
  f[f.size() - 1] = "-50.0";
  std::string changed;
  for (const auto& w : f) changed += (changed.empty() ? "" : " ") + w;
  text.replace(last, eol - last, changed);
  const fs::path log = Fresh("backward.clf");
  std::ofstream(log) << text;
  const fs::path dir = Fresh("backward");
  const Result r = Lifelong("replay " + log.string() + " --modes standard -o " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("1 scans are stamped earlier"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(log.string() + ":"), std::string::npos) << r.output;
  const auto summary = nlohmann::json::parse(Read(dir / "summary.json"));
  EXPECT_EQ(summary["log"]["backward_stamps"].get<int>(), 1);
  // Out of order, but every stamp its own: no word about shared stamps.
  EXPECT_EQ(summary["log"]["distinct_stamps"], summary["log"]["scans"]);
  EXPECT_EQ(r.output.find("share their stamps"), std::string::npos) << r.output;
  EXPECT_GT(summary["log_duration_s"].get<double>(), 0.0);
}

// run --seed simulates with that seed instead of the scenario's: the same run as a scenario
// copy that names the seed (what a sweep's cell writes).
TEST(Cli, RunWithASeedIsTheScenarioWithThatSeed) {
  std::string text = Read(kScenario);
  for (const auto& [key, value] :
       {std::pair<std::string, std::string>{"seed", "3"},  // corridor_3's own is 7
        {"world", kSource + "/worlds/corridor.yaml"}}) {
    const auto at = text.find("\n" + key + ":");
    ASSERT_NE(at, std::string::npos) << "corridor_3.yaml names its " << key;
    text.replace(at, text.find('\n', at + 1) - at, "\n" + key + ": " + value);
  }
  const fs::path copy = Fresh("seed3.yaml");
  std::ofstream(copy) << text;
  const fs::path by_option = Fresh("seed_option"), by_file = Fresh("seed_file");
  Result r = Lifelong("run " + kScenario + " --modes standard --seed 3 -o " + by_option.string());
  ASSERT_EQ(r.code, 0) << r.output;
  r = Lifelong("run " + copy.string() + " --modes standard -o " + by_file.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(nlohmann::json::parse(Read(by_option / "summary.json"))["seed"].get<int>(), 3);
  EXPECT_EQ(Read(by_option / "standard" / "trajectory.tum"),
            Read(by_file / "standard" / "trajectory.tum"));
}

// replay --seed replays a draw of the log: its odometry perturbed, its seed recorded; the log
// as recorded has no seed.
TEST(Cli, ReplayWithASeedReplaysADrawAndRecordsIt) {
  const fs::path recorded = Fresh("recorded"), drawn = Fresh("drawn");
  Result r =
      Lifelong("replay " + CorridorLog().string() + " --modes standard -o " + recorded.string());
  ASSERT_EQ(r.code, 0) << r.output;
  r = Lifelong("replay " + CorridorLog().string() + " --modes standard --seed 2 -o " +
               drawn.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const auto a = nlohmann::json::parse(Read(recorded / "summary.json"));
  const auto b = nlohmann::json::parse(Read(drawn / "summary.json"));
  EXPECT_FALSE(a["log"].contains("draw_seed"));
  EXPECT_EQ(b["log"]["draw_seed"].get<int>(), 2);
  EXPECT_EQ(b["seed"].get<int>(), 2);
  EXPECT_NE(Read(recorded / "standard" / "trajectory.tum"),
            Read(drawn / "standard" / "trajectory.tum"));
  EXPECT_NE(
      Lifelong("replay " + CorridorLog().string() + " --seed -1 -o " + Fresh("neg").string()).code,
      0);
}

TEST(Cli, AScanWithNoBeamsIsAnInputErrorNamingTheLine) {
  const fs::path log = Fresh("zero.clf");
  std::ofstream(log) << "FLASER 3 1 1 1 0 0 0 0 0 0 1.0 h 1.0\nFLASER 0 0 0 0 0 0 0 2.0 h 2.0\n";
  const Result r = Lifelong("replay " + log.string() + " -o " + Fresh("zero").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(log.string() + ":2"), std::string::npos) << r.output;
}

TEST(Cli, AnEmptyGraphIsAnInputError) {
  const fs::path g = Fresh("empty.g2o");
  std::ofstream(g) << "";
  const fs::path out = Fresh("empty_out.g2o");
  const Result r = Lifelong("optimize " + g.string() + " -o " + out.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(r.output.find("converged"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, HelpShowsEveryDefault) {
  Result r = Lifelong("run --help");
  EXPECT_EQ(r.code, 0);
  for (const char* d : {"runs/latest", "standard,pruned", "corridor_100.yaml", "20"}) {
    EXPECT_NE(r.output.find(d), std::string::npos) << d << "\n" << r.output;
  }
  r = Lifelong("replay --help");
  EXPECT_NE(r.output.find("runs/replay"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("standard,pruned"), std::string::npos) << r.output;
  r = Lifelong("optimize --help");
  EXPECT_NE(r.output.find("lm"), std::string::npos) << r.output;
}

TEST(Cli, VersionNamesTheVersionAndTheCommit) {
  const Result r = Lifelong("--version");
  EXPECT_EQ(r.code, 0);
  // "lifelong X.Y.Z (commit C)" (no <regex>: GCC 12 warns inside it under the sanitizers)
  std::istringstream words(r.output);
  std::string name, version, commit_word, commit;
  words >> name >> version >> commit_word >> commit;
  EXPECT_TRUE(name == "lifelong" && std::count(version.begin(), version.end(), '.') == 2 &&
              commit_word == "(commit" && commit.size() > 1 && commit.back() == ')')
      << r.output;
}

TEST(Cli, UnknownCommandsAndBadValuesAreNamedReadably) {
  Result r = Lifelong("foo");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("unknown command foo"), std::string::npos) << r.output;
  r = Lifelong("run " + kScenario + " --stride 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("from 1 to 1000000"), std::string::npos) << r.output;
  int run = 0, longest = 0;  // the longest run of digits: no 300-digit bound
  for (char c : r.output) longest = std::max(longest, run = std::isdigit(c) ? run + 1 : 0);
  EXPECT_LT(longest, 20) << r.output;
  r = Lifelong("run " + kScenario + " --modes 'standard, bogus'");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.output.find("bogus"), std::string::npos) << r.output;
}

}  // namespace
