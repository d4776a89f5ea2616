// A run whose robot did not drive its scenario (a collision, a route that timed out) must
// not look like a result: `run` exits 1, summary.json says what happened, and a sweep keeps
// the cell out of its tables. Options that would be ignored, and empty or unwritable output
// paths, exit 2 before any work.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "run_lifelong.hpp"

namespace {

namespace fs = std::filesystem;

using lifelong::test::Lifelong;
using lifelong::test::Read;
using lifelong::test::Result;
const std::string kSource = LIFELONG_SOURCE_DIR;
const std::string kScenario = kSource + "/scenarios/corridor_3.yaml";

fs::path Fresh(const std::string& name) { return lifelong::test::FreshPath("failed_run_", name); }

fs::path WriteFile(const std::string& name, const std::string& text) {
  return lifelong::test::WriteFresh("failed_run_", name, text);
}

// Refused as bad input before the simulation started.
void ExpectRefusedFirst(const Result& r, const std::string& names) {
  lifelong::test::ExpectInputError(r, names);
  EXPECT_EQ(r.output.find("simulating"), std::string::npos) << "not before any work\n" << r.output;
}

// A 9 m corridor whose crate slides across it at t = 3 s, before the robot gets there.
constexpr const char* kBlockedWorld = R"(walls:
  - polyline: [[0, 0], [9, 0], [9, 3], [0, 3], [0, 0]]
boxes:
  - name: crate
    center: [6.5, 4.5]
    size: [0.8, 0.8]
    moves: [{t_s: 3, center: [6.5, 1.5]}]
places:
  - {name: west, at: [1.0, 1.5]}
  - {name: east, at: [8.0, 1.5]}
roadmap:
  - [west, east]
)";

std::string BlockedScenario(bool expected) {
  return std::string("name: blocked\nworld: failed_run_blocked_world.yaml\nseed: 1\n") +
         (expected ? "collisions_expected: true\n" : "") +
         "route: {type: path, waypoints: [west, east]}\n";
}

TEST(FailedRunCli, ACollisionFailsTheRunAndIsInItsSummary) {
  WriteFile("blocked_world.yaml", kBlockedWorld);
  const fs::path scenario = WriteFile("blocked.yaml", BlockedScenario(false));
  const fs::path out = Fresh("blocked_out");
  const Result r = Lifelong("run " + scenario.string() + " --modes standard -o " + out.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("collision"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("box crate"), std::string::npos) << r.output;
  // The figures are written, for a look, and say what happened.
  const auto summary = nlohmann::json::parse(Read(out / "summary.json"));
  ASSERT_TRUE(summary.contains("simulation")) << summary.dump(2);
  const auto& sim = summary["simulation"];
  EXPECT_TRUE(sim["failed"].get<bool>());
  EXPECT_TRUE(sim["collided"].get<bool>());
  EXPECT_FALSE(sim["collisions_expected"].get<bool>());
  EXPECT_GE(sim["collisions"].get<int>(), 1);
  EXPECT_GE(sim["first_collision"]["t_s"].get<double>(), 3.0);
  EXPECT_NE(sim["first_collision"]["with"].get<std::string>().find("crate"), std::string::npos);
  EXPECT_TRUE(sim["timed_out"].get<bool>()) << "the crate never moves away";
  EXPECT_GT(sim["duration_s"].get<double>(), sim["expected_duration_s"].get<double>());
}

TEST(FailedRunCli, ACollisionTheScenarioExpectsIsNoteOnlyButATimeoutStillFails) {
  WriteFile("blocked_world.yaml", kBlockedWorld);
  const fs::path scenario = WriteFile("expected.yaml", BlockedScenario(true));
  const fs::path out = Fresh("expected_out");
  const Result r = Lifelong("run " + scenario.string() + " --modes standard -o " + out.string());
  EXPECT_EQ(r.code, 1) << "the route still timed out\n" << r.output;
  const auto summary = nlohmann::json::parse(Read(out / "summary.json"));
  EXPECT_TRUE(summary["simulation"]["collisions_expected"].get<bool>());
}

TEST(FailedRunCli, AnUntouchedRunSaysSoAndExitsZero) {
  const fs::path scenario = WriteFile("short.yaml", "name: short\nworld: " + kSource +
                                                        "/worlds/corridor.yaml\nseed: 1\n"
                                                        "route: {type: path, waypoints: [west, "
                                                        "middle]}\n");
  const fs::path out = Fresh("short_out");
  const Result r = Lifelong("run " + scenario.string() + " --modes standard -o " + out.string());
  EXPECT_EQ(r.code, 0) << r.output;
  const auto summary = nlohmann::json::parse(Read(out / "summary.json"));
  EXPECT_FALSE(summary["simulation"]["failed"].get<bool>());
  EXPECT_FALSE(summary["simulation"]["collided"].get<bool>());
  EXPECT_FALSE(summary["simulation"].contains("first_collision"));
}

// A sweep over a scenario whose robot collides reports the cell failed and aggregates nothing.
TEST(FailedRunCli, ASweepNeverAggregatesACollidedRun) {
  WriteFile("blocked_world.yaml", kBlockedWorld);
  const fs::path scenario = WriteFile("blocked.yaml", BlockedScenario(false));
  const fs::path spec = WriteFile("blocked_sweep.yaml", "scenarios: [" + scenario.string() +
                                                            "]\nseeds: [1]\nmodes: [standard]\n");
  const fs::path out = Fresh("blocked_sweep");
  const Result r = Lifelong("sweep " + spec.string() + " -o " + out.string() + " -j 1");
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("1 failed"), std::string::npos) << r.output;
  const std::string runs = Read(out / "runs.csv");
  EXPECT_EQ(runs.find("blocked"), std::string::npos) << runs;
}

TEST(FailedRunCli, ARouteOfOnePlaceIsRefused) {
  const fs::path scenario = WriteFile("one_place.yaml", "name: one\nworld: " + kSource +
                                                            "/worlds/corridor.yaml\nseed: 1\n"
                                                            "route:\n  type: back_and_forth\n"
                                                            "  waypoints: [west, west]\n");
  ExpectRefusedFirst(Lifelong("run " + scenario.string() + " -o " + Fresh("one").string()),
                     "field 'route.waypoints[1]': waypoint is where waypoint 0 is");
}

TEST(FailedRunCli, DuplicateDoorOrBoxNamesAreRefused) {
  const fs::path world = WriteFile("dup_world.yaml", R"(walls:
  - polyline: [[0, 0], [9, 0], [9, 3], [0, 3], [0, 0]]
doors:
  - {name: lab, from: [3, 0], to: [4, 0]}
boxes:
  - {name: lab, center: [6, 1], size: [0.5, 0.5]}
places:
  - {name: west, at: [1.0, 1.5]}
  - {name: east, at: [8.0, 1.5]}
)");
  const fs::path scenario = WriteFile("dup.yaml",
                                      "name: dup\nworld: failed_run_dup_world.yaml\nseed: 1\n"
                                      "route: {type: path, waypoints: [west, east]}\n");
  ExpectRefusedFirst(
      Lifelong("run " + scenario.string() + " -o " + Fresh("dup").string()),
      "failed_run_dup_world.yaml:6: field 'boxes[0].name': duplicate door or box name 'lab'");
}

TEST(FailedRunCli, OptionsThatWouldBeIgnoredAreRefused) {
  ExpectRefusedFirst(Lifelong("run " + kScenario + " --stride 5 -o " + Fresh("s").string()),
                     "--stride does nothing without --video or --frames");
  const std::string log = kSource + "/tests/data/io/tiny.clf";
  ExpectRefusedFirst(Lifelong("replay " + log + " --relations-offset 3 -o " + Fresh("r").string()),
                     "--relations-offset does nothing without --relations");
  ExpectRefusedFirst(Lifelong("replay " + log + " --relations x.rel --relations-offset '' -o " +
                              Fresh("r").string()),
                     "--relations-offset: expected a finite number, got ''");
  ExpectRefusedFirst(Lifelong("sparsify g.g2o --method chow-liu --keep-share 0.5 --nfr-chords mi"),
                     "--nfr-chords does nothing without --method nfr-subgraph");
}

TEST(FailedRunCli, AnEmptyOutputPathIsNamedAsEmpty) {
  for (const char* command :
       {"run", "replay x.clf", "simulate " LIFELONG_SOURCE_DIR "/scenarios/corridor_3.yaml",
        "optimize x.g2o", "sparsify x.g2o --keep-share 0.5"}) {
    const Result r = Lifelong(std::string(command) + " -o ''");
    EXPECT_EQ(r.code, 2) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("the path is empty"), std::string::npos) << command << "\n" << r.output;
  }
}

// optimize -o and sparsify -o into a place that cannot be written fail before the work,
// with the reason.
TEST(FailedRunCli, AnUnwritableGraphOutputIsRefusedBeforeTheWork) {
  const fs::path graph = WriteFile("tiny.g2o",
                                   "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nVERTEX_SE2 2 2 0 0\n"
                                   "EDGE_SE2 0 1 1 0 0 100 0 0 100 0 100\n"
                                   "EDGE_SE2 1 2 1 0 0 100 0 0 100 0 100\n");
  const fs::path file = WriteFile("plain_file", "x");
  const std::string under_file = (file / "out.g2o").string();
  Result r = Lifelong("optimize " + graph.string() + " -o " + under_file);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(under_file), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("vertices"), std::string::npos) << "the job ran first\n" << r.output;
  r = Lifelong("sparsify " + graph.string() + " --keep-share 0.5 -o " + under_file);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find(under_file), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("kld"), std::string::npos) << "the job ran first\n" << r.output;
}

// Every matcher setting at the end of its range asks for tables of tens of GiB: refused at
// load, naming the fields, not a bad_alloc after minutes.
TEST(FailedRunCli, AMatcherWhoseTablesCannotFitIsRefusedAtLoad) {
  const fs::path config = WriteFile("huge.yaml",
                                    "incremental:\n  matcher:\n    linear_window_m: 50\n"
                                    "    resolution_m: 0.005\n    angular_window_rad: 3.14159\n"
                                    "    angular_step_rad: 0.0001\n");
  ExpectRefusedFirst(
      Lifelong("run " + kScenario + " --config " + config.string() + " -o " + Fresh("h").string()),
      "incremental.matcher.linear_window_m, incremental.matcher.resolution_m");
  const fs::path loops = WriteFile(
      "huge_loops.yaml", "loops:\n  max_window_m: 50\n  matcher:\n    resolution_m: 0.005\n");
  ExpectRefusedFirst(
      Lifelong("run " + kScenario + " --config " + loops.string() + " -o " + Fresh("h").string()),
      "loops.max_window_m");
  const fs::path places =
      WriteFile("huge_places.yaml", "loops:\n  global:\n    rings: 1000\n    sectors: 3600\n");
  ExpectRefusedFirst(
      Lifelong("run " + kScenario + " --config " + places.string() + " -o " + Fresh("h").string()),
      "loops.global.rings, loops.global.sectors");
}

// A SIGTERM in the middle of a step that never returns to a poll (one scan matched over a
// window of 8 m in 1 cm cells at every heading takes minutes) is answered within the grace
// of 1 s, and the staging directory goes with the process. It was unanswered for 142 s.
TEST(FailedRunCli, ASignalInALongStepIsAnsweredAndLeavesNoStagingDirectory) {
  const fs::path config =
      WriteFile("slow.yaml",
                "incremental:\n  matcher:\n    linear_window_m: 8\n    resolution_m: 0.01\n"
                "    angular_window_rad: 3.0\n");
  const fs::path out = Fresh("slow_out");
  const std::string bin = LIFELONG_BIN;
  std::vector<std::string> args = {bin,       "run",      kScenario, "--config",  config.string(),
                                   "--modes", "standard", "-o",      out.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  ASSERT_EQ(posix_spawn(&pid, bin.c_str(), &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  const fs::path staging = out.string() + ".partial-" + std::to_string(pid);
  // The mapper starts once the staging directory exists; give it a moment to be in a match.
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  while (!fs::exists(staging) && Clock::now() - start < std::chrono::seconds(60)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(fs::exists(staging));
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  const auto signalled = Clock::now();
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0 &&
         Clock::now() - signalled < std::chrono::seconds(30)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double answered_s = std::chrono::duration<double>(Clock::now() - signalled).count();
  if (answered_s >= 30.0) ::kill(pid, SIGKILL), ::waitpid(pid, &status, 0);
  // 1 s of grace; the bound leaves room for a loaded machine, far from the 142 s it was.
  EXPECT_LT(answered_s, 10.0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM) << status;
  EXPECT_FALSE(fs::exists(staging));
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
