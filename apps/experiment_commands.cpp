// liblifelong_commands.so: `lifelong run`, `replay`, `simulate` (apps/commands.hpp) and
// `sweep` (apps/sweep_command.cpp).
// Loaded by the `lifelong` program on demand; it brings the simulator, the evaluation,
// OpenCV and offscreen OpenGL with it.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <utility>

#include "apps/commands.hpp"
#include "apps/exit_codes.hpp"
#include "apps/reproduce_command.hpp"
#include "apps/score_command.hpp"
#include "apps/sweep_command.hpp"
#include "apps/video_module.hpp"
#include "eval/common/interrupt.hpp"
#include "eval/common/staged_output.hpp"
#include "eval/experiment/experiment.hpp"
#include "eval/experiment/log_draw.hpp"
#include "eval/experiment/mapper_config_file.hpp"
#include "eval/experiment/simulation.hpp"
#include "eval/report/console_table.hpp"
#include "eval/truth/world_state.hpp"
#include "io/carmen_log.hpp"
#include "io/output_path.hpp"
#include "io/relations.hpp"
#include "io/relations_offset.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"
#include "sim/scenario.hpp"

namespace lifelong::apps {
namespace {

namespace fs = std::filesystem;
using lifelong::InputError;

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// "standard, pruned" and "standard,pruned" alike; a mode named twice is an error.
std::vector<lifelong::slam::Mode> ParseModes(const std::string& list) {
  std::vector<lifelong::slam::Mode> modes;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const std::string name = Trim(item);
    const std::optional<lifelong::slam::Mode> mode = lifelong::slam::ParseMode(name);
    if (!mode) {
      throw InputError("--modes", 0, name,
                       "unknown mode (known: " + lifelong::slam::ModeList() + ")");
    }
    if (std::any_of(modes.begin(), modes.end(),
                    [&](const lifelong::slam::Mode& m) { return m.name == mode->name; })) {
      throw InputError("--modes", 0, name, "mode named twice");
    }
    modes.push_back(*mode);
  }
  if (modes.empty()) throw InputError("--modes", 0, "", "no mode given");
  return modes;
}

// The cell side of the truth map `simulate` writes beside its log.
constexpr double kSimulateTruthResolutionM = 0.05;

bool StderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

void PrintResult(const lifelong::eval::RunSummary& summary, const std::string& out) {
  std::cout << lifelong::eval::ConsoleTable(summary) << "wrote " << out
            << "/summary.json and report.html\n";
}

int Simulate(const std::string& scenario_path, const std::string& out) {
  const lifelong::sim::Scenario scenario = lifelong::sim::LoadScenario(scenario_path);
  lifelong::eval::CheckWorldRaster(scenario, kSimulateTruthResolutionM);
  lifelong::io::CheckWritableFile(out);
  std::cerr << "simulating " << scenario.name << " (" << scenario.duration_s << " s expected)\n";
  const auto run = lifelong::eval::SimulateScenario(scenario, &std::cerr, StderrIsTerminal());
  lifelong::eval::WriteSimulation(out, scenario, run, kSimulateTruthResolutionM);
  std::cout << "scans " << run.observations.size() << "  odometry " << run.odometry.size()
            << "  simulated " << run.duration_s << " s  collisions " << run.collisions.size()
            << (run.timed_out ? "  (timed out)" : "") << "\n";
  for (const auto& c : run.collisions) {
    std::cout << "collision at t = " << c.stamp_s << " s with " << c.what << " at ("
              << c.T_world_robot.x << ", " << c.T_world_robot.y << ")\n";
  }
  std::cout << "wrote " << out << " and its .truth.tum, .truth.pgm/.yaml, .truth.*.tsv and .png\n";
  return lifelong::eval::Outcome(scenario, run).Failed() ? 1 : 0;
}

// Settings every experiment shares; inputs are all checked here, before any work.
lifelong::eval::ExperimentConfig ExperimentSettings(const std::string& out,
                                                    const std::string& modes,
                                                    const std::string& config_path,
                                                    const std::string& command_line) {
  lifelong::eval::ExperimentConfig config;
  if (!config_path.empty()) {  // else the defaults (configs/default.yaml)
    lifelong::eval::ConfigFile file = lifelong::eval::LoadConfigFile(config_path);
    config.mapper = std::move(file.mapper);
    config.false_closures = file.false_closures;
  }
  config.modes = ParseModes(modes);
  lifelong::eval::CheckReplaceableOutput(out);
  config.out_dir = out;
  config.command_line = command_line;
  config.progress = &std::cerr;
  config.progress_terminal = StderrIsTerminal();
  return config;
}

int Run(const RunArgs& a) {
  lifelong::eval::ExperimentConfig config =
      ExperimentSettings(a.out, a.modes, a.config, a.command_line);
  config.present_at_s = a.present_at;
  std::sort(config.present_at_s.begin(), config.present_at_s.end());
  config.video_path = a.video;
  config.frames_dir = a.frames;
  config.video_stride = a.stride;
  if (!a.video.empty() || !a.frames.empty()) config.open_video = LoadVideoModule();
  if (!a.video.empty()) lifelong::io::CheckWritableFile(a.video, "--video");
  if (!a.frames.empty()) lifelong::io::CheckWritableDirectory(a.frames, "--frames");
  lifelong::sim::Scenario scenario = lifelong::sim::LoadScenario(a.scenario);
  if (a.seed) scenario.seed = static_cast<std::uint64_t>(*a.seed);  // as a sweep's cell does
  lifelong::eval::CheckWorldRaster(scenario, config.mapper.grid.resolution_m);
  std::cerr << "simulating " << scenario.name << " (" << scenario.duration_s << " s expected)\n";
  const auto run = lifelong::eval::SimulateScenario(scenario, &std::cerr, config.progress_terminal);
  const lifelong::eval::SimulationOutcome outcome = lifelong::eval::Outcome(scenario, run);
  config.simulation = outcome;
  config.source = a.scenario;
  config.seed = static_cast<std::int64_t>(scenario.seed);
  config.first_pass_s = lifelong::eval::FirstPassEnd(scenario, run);
  if (!config.first_pass_s) {
    std::cerr << "note: the tour never visits every destination: no first pass is reported\n";
  }
  for (const double t : config.present_at_s) {
    if (t > run.duration_s) {
      std::cerr << "note: --present-at " << t << " s is after the run's end (" << run.duration_s
                << " s): not scored\n";
    }
  }
  const lifelong::eval::GroundTruth truth = lifelong::eval::TruthOf(scenario.world, run.duration_s);
  PrintResult(lifelong::eval::RunExperiment(run.observations, truth, config), a.out);
  if (outcome.collided || outcome.timed_out) {
    std::cerr << (outcome.Failed() ? "error: " : "note: ") << "the robot did not drive "
              << a.scenario << " as scripted: " << lifelong::eval::OutcomeText(outcome)
              << (outcome.Failed() ? "the figures in " + a.out + " are of that run (exit 1)\n"
                                   : "");
  }
  return outcome.Failed() ? 1 : 0;
}

// The scans' stamps, ascending.
std::vector<double> SortedScanStamps(const lifelong::io::CarmenLog& data) {
  std::vector<double> stamps;
  for (const auto& o : data.observations) stamps.push_back(o.stamp_s);
  std::sort(stamps.begin(), stamps.end());
  return stamps;
}

// Reads the relations and puts them in log time: with the given offset, or the one that
// puts relation stamps on scan stamps. No matching relation is an input error, never a
// zero error figure.
std::vector<lifelong::Relation> LoadRelations(const std::string& path, bool given, double given_s,
                                              const std::vector<double>& stamps,
                                              lifelong::eval::LogInfo* info) {
  const auto file_time = lifelong::io::ReadRelations(path, 0.0);
  const lifelong::io::OffsetDetection d =
      given ? lifelong::io::OffsetDetection{given_s,
                                            lifelong::io::CountMatchedRelations(file_time, stamps,
                                                                                given_s),
                                            {}}
            : lifelong::io::DetectRelationsOffset(file_time, stamps);
  std::ostringstream what;
  what << std::setprecision(16) << "no relation has both stamps on a scan of the log ("
       << file_time.size() << " relations, " << stamps.size() << " scans"
       << (given ? ", --relations-offset " + std::to_string(given_s) + " s" : "") << ")";
  if (d.matched == 0) throw InputError(path, 0, "--relations-offset", what.str());
  if (d.also_fits_s) {
    std::ostringstream both;
    both << std::setprecision(16) << "the clock cannot be told from the stamps: offsets "
         << d.offset_s << " s and " << *d.also_fits_s << " s both put " << d.matched
         << " relations on scans (scans at a regular rate); give --relations-offset";
    throw InputError(path, 0, "--relations-offset", both.str());
  }
  // Relations that belong to the log land on its scans; an offset or a file that puts few of
  // those inside the log's span on scans is scored on a handful by chance.
  const std::size_t inside = lifelong::io::CountRelationsInside(
      file_time, stamps.front() - lifelong::io::kRelationStampToleranceS,
      stamps.back() + lifelong::io::kRelationStampToleranceS, d.offset_s);
  if (2 * d.matched < inside) {
    std::ostringstream few;
    few << std::setprecision(16) << "only " << d.matched << " of the " << inside
        << " relations whose stamps fall inside the log's span land on its scans (offset "
        << d.offset_s << " s, " << (given ? "given" : "detected") << "; " << file_time.size()
        << " in the file): the relations do not belong to this log or this clock";
    throw InputError(path, 0, "--relations-offset", few.str());
  }
  std::cerr << std::setprecision(16) << "relations: " << d.matched << " of " << file_time.size()
            << " on scans of the log, offset " << d.offset_s << " s ("
            << (given ? "given" : "detected") << ")\n";
  info->relations_offset_s = d.offset_s;
  info->relations_offset_detected = !given;
  info->relations_in_file = static_cast<std::int64_t>(file_time.size());
  return lifelong::io::ShiftRelations(file_time, d.offset_s);
}

// What the log holds, told on stderr and kept for summary.json's "log" object.
// `stamps`: the scans' stamps, ascending.
lifelong::eval::LogInfo DescribeLog(const lifelong::io::CarmenLog& data, const std::string& log,
                                    const std::vector<double>& stamps) {
  std::cerr << "read " << data.observations.size() << " scans from " << log
            << (data.odometry_recovered ? " (raw odometry recovered from a corrected log)" : "")
            << "\n";
  if (!data.skipped.empty()) {
    std::cerr << "note: lines of other message types were skipped:";
    for (const auto& [type, count] : data.skipped) std::cerr << " " << type << " " << count;
    std::cerr << "\n";
  }
  if (data.observations.empty()) throw InputError(log, 0, "", "the log holds no laser scans");
  lifelong::eval::LogInfo info;
  info.scans = static_cast<std::int64_t>(data.observations.size());
  info.backward_stamps = data.backward_scan_stamps;
  info.odometry_lost = data.lost_odometry_scans;
  info.distinct_stamps = 0;
  for (std::size_t i = 0; i < stamps.size(); ++i)
    info.distinct_stamps += (i == 0 || stamps[i] != stamps[i - 1]) ? 1 : 0;
  if (data.lost_odometry_scans > 0) {
    std::cerr << "note: " << data.lost_odometry_scans
              << " scans have no odometry of their own (first: " << log << ":"
              << data.first_lost_odometry_line
              << "); the mapper searches their step over a full turn\n";
  }
  if (data.backward_scan_stamps > 0) {
    std::cerr << "warning: " << data.backward_scan_stamps
              << " scans are stamped earlier than the scan before them (first: " << log << ":"
              << data.first_backward_scan_line << "); they are replayed in file order\n";
  }
  if (info.distinct_stamps < info.scans) {
    std::cerr << "warning: the log's scans share their stamps (" << info.distinct_stamps
              << " distinct of " << info.scans
              << "); the trajectory files carry them as they are, so pair them by line, not "
                 "by time\n";
  }
  return info;
}

int Replay(const ReplayArgs& a) {
  const std::string& log = a.log;
  lifelong::eval::ExperimentConfig config =
      ExperimentSettings(a.out, a.modes, a.config, a.command_line);
  // Read before the log, so that a bad reference costs no wait.
  if (!a.reference.empty()) config.reference = lifelong::io::ReadTrajectory(a.reference);
  lifelong::io::CarmenLog data = lifelong::io::ReadCarmenLog(log);
  const std::vector<double> stamps = SortedScanStamps(data);
  lifelong::eval::LogInfo info = DescribeLog(data, log, stamps);
  if (a.seed) {
    lifelong::eval::DrawOdometry(static_cast<std::uint64_t>(*a.seed), {}, &data.observations);
    info.draw_seed = *a.seed;
    config.seed = *a.seed;
    std::cerr << "draw " << *a.seed << ": each odometry step perturbed (replay --seed)\n";
  }
  if (!a.relations.empty())
    config.relations = LoadRelations(a.relations, a.offset_given, a.offset_s, stamps, &info);
  if (!a.reference.empty()) {
    if (2 * info.distinct_stamps <= info.scans) {
      throw InputError(log, 0, "--reference",
                       "the log's scans share their stamps (" +
                           std::to_string(info.distinct_stamps) + " distinct of " +
                           std::to_string(info.scans) +
                           "): a reference cannot be paired with them by time");
    }
    info.reference = a.reference;
  } else if (data.odometry_recovered) {
    config.reference = data.corrected_poses;
    config.reference_per_scan = data.corrected_poses.size() == data.observations.size();
    info.reference = "corrected FLASER poses";
  }
  if (!config.reference.empty()) {
    info.reference_poses = static_cast<std::int64_t>(config.reference.size());
    std::cerr << "reference: " << config.reference.size() << " poses (" << *info.reference
              << "); ATE and RPE at 1 m are scored against it\n";
  }
  config.source = log;
  config.log = info;
  PrintResult(lifelong::eval::RunExperiment(data.observations, std::nullopt, config), a.out);
  return 0;
}

template <typename F>
int Command(F&& f) {
  eval::InstallInterruptHandler();
  return Guarded(std::forward<F>(f), [](const std::exception& e) {
    return dynamic_cast<const eval::Interrupted*>(&e) != nullptr;
  });
}

int RunCommand(const RunArgs& a) {
  return Command([&] { return Run(a); });
}
int SimulateCommand(const SimulateArgs& a) {
  return Command([&] { return Simulate(a.scenario, a.out); });
}
int ReplayCommand(const ReplayArgs& a) {
  return Command([&] { return Replay(a); });
}

const CommandTable kTable{RunCommand,   SimulateCommand, ReplayCommand,
                          SweepCommand, ScoreCommand,    ReproduceCommand};

}  // namespace
}  // namespace lifelong::apps

extern "C" __attribute__((visibility("default"))) const lifelong::apps::CommandTable*
lifelong_command_table_v5() {
  return &lifelong::apps::kTable;
}
