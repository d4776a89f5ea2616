// lifelong: the command-line front of the testbed. Thin: parses arguments and calls eval.
// Exit codes (DESIGN.md): 0 success, 2 bad input or usage, 1 internal failure.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "eval/console_table.hpp"
#include "eval/experiment.hpp"
#include "eval/interrupt.hpp"
#include "eval/mapper_config_file.hpp"
#include "eval/simulation.hpp"
#include "eval/staged_output.hpp"
#include "io/carmen_log.hpp"
#include "io/graph_file.hpp"
#include "io/relations.hpp"
#include "io/relations_offset.hpp"
#include "sensor/input_error.hpp"
#include "sim/scenario.hpp"
#include "slam/optimizer.hpp"

namespace {

namespace fs = std::filesystem;
using lifelong::InputError;

constexpr const char* kDefaultScenario = LIFELONG_SOURCE_DIR "/scenarios/corridor_100.yaml";

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// "standard, pruned" and "standard,pruned" alike; a mode named twice is an error.
std::vector<lifelong::slam::PruningMode> ParseModes(const std::string& list) {
  std::vector<lifelong::slam::PruningMode> modes;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const std::string name = Trim(item);
    lifelong::slam::PruningMode mode;
    if (!lifelong::slam::ParsePruningMode(name, &mode)) {
      throw InputError("--modes", 0, name,
                       "unknown mode (known: standard, pruned, pruned-exact, pruned-naive)");
    }
    if (std::find(modes.begin(), modes.end(), mode) != modes.end()) {
      throw InputError("--modes", 0, name, "mode named twice");
    }
    modes.push_back(mode);
  }
  if (modes.empty()) throw InputError("--modes", 0, "", "no mode given");
  return modes;
}

// Fails early (exit 2) when a file cannot be written at `path`: checked before a long
// simulation, not after it.
void CheckWritableFile(const std::string& path) {
  const fs::path p(path);
  if (p.filename().empty()) throw InputError(path, 0, "-o", "names a directory, not a file");
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw InputError(path, 0, "-o", "is a directory");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  fs::create_directories(dir, ec);
  const fs::path probe = dir / (".lifelong-write-test-" + std::to_string(::getpid()));
  std::FILE* f = ec ? nullptr : std::fopen(probe.c_str(), "w");
  if (!f) throw InputError(path, 0, "-o", "cannot write in " + dir.string());
  std::fclose(f);
  fs::remove(probe, ec);
}

std::string CommandLine(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

bool StderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

void PrintResult(const lifelong::eval::RunSummary& summary, const std::string& out) {
  std::cout << lifelong::eval::ConsoleTable(summary) << "wrote " << out
            << "/summary.json and report.html\n";
}

int Simulate(const std::string& scenario_path, const std::string& out) {
  const lifelong::sim::Scenario scenario = lifelong::sim::LoadScenario(scenario_path);
  CheckWritableFile(out);
  std::cerr << "simulating " << scenario.name << " (" << scenario.duration_s << " s expected)\n";
  const auto run = lifelong::eval::SimulateScenario(scenario, &std::cerr, StderrIsTerminal());
  lifelong::eval::WriteSimulation(out, scenario, run, 0.05);
  std::cout << "scans " << run.observations.size() << "  odometry " << run.odometry.size()
            << "  simulated " << run.duration_s << " s  collisions " << run.collisions.size()
            << (run.timed_out ? "  (timed out)" : "") << "\n";
  for (const auto& c : run.collisions) {
    std::cout << "collision at t = " << c.stamp_s << " s with " << c.what << " at ("
              << c.T_world_robot.x << ", " << c.T_world_robot.y << ")\n";
  }
  std::cout << "wrote " << out << " and its .truth.tum, .truth.pgm/.yaml and .png\n";
  return run.collisions.empty() && !run.timed_out ? 0 : 1;
}

struct VideoArgs {
  std::string video, frames;
  int stride = 20;
};

// Mapper settings: the defaults, or a YAML file over them (configs/default.yaml).
lifelong::slam::MapperConfig MapperSettings(const std::string& config_path) {
  return config_path.empty() ? lifelong::slam::DefaultMapperConfig()
                             : lifelong::eval::LoadMapperConfig(config_path);
}

// Settings every experiment shares; inputs are all checked here, before any work.
lifelong::eval::ExperimentConfig ExperimentSettings(const std::string& out,
                                                    const std::string& modes,
                                                    const std::string& config_path,
                                                    const std::string& command_line) {
  lifelong::eval::ExperimentConfig config;
  config.mapper = MapperSettings(config_path);
  config.modes = ParseModes(modes);
  lifelong::eval::CheckReplaceableOutput(out);
  config.out_dir = out;
  config.command_line = command_line;
  config.progress = &std::cerr;
  config.progress_terminal = StderrIsTerminal();
  return config;
}

int Run(const std::string& scenario_path, const std::string& out, const std::string& modes,
        const std::string& config_path, const VideoArgs& video, const std::string& command_line) {
  lifelong::eval::ExperimentConfig config =
      ExperimentSettings(out, modes, config_path, command_line);
  config.video_path = video.video;
  config.frames_dir = video.frames;
  config.video_stride = video.stride;
  if (!video.video.empty()) CheckWritableFile(video.video);
  const lifelong::sim::Scenario scenario = lifelong::sim::LoadScenario(scenario_path);
  std::cerr << "simulating " << scenario.name << " (" << scenario.duration_s << " s expected)\n";
  const auto run = lifelong::eval::SimulateScenario(scenario, &std::cerr, config.progress_terminal);
  for (const auto& c : run.collisions) {
    std::cerr << "warning: collision at t = " << c.stamp_s << " s with " << c.what << "\n";
  }
  config.source = scenario_path;
  config.seed = static_cast<std::int64_t>(scenario.seed);
  config.first_pass_s = lifelong::eval::FirstPassEnd(scenario, run);
  if (!config.first_pass_s) {
    std::cerr << "note: the tour never visits every destination: no first pass is reported\n";
  }
  const lifelong::eval::GroundTruth truth{
      lifelong::eval::TrueWalls(scenario.world, run.duration_s)};
  PrintResult(lifelong::eval::RunExperiment(run.observations, truth, config), out);
  return 0;
}

// Reads the relations and puts them in log time: with the given offset, or the one that
// puts relation stamps on scan stamps. No matching relation is an input error, never a
// zero error figure.
std::vector<lifelong::io::Relation> LoadRelations(const std::string& path, bool given,
                                                  double given_s,
                                                  const lifelong::io::CarmenLog& data,
                                                  lifelong::eval::LogInfo* info) {
  const auto file_time = lifelong::io::ReadRelations(path, 0.0);
  std::vector<double> stamps;
  for (const auto& o : data.observations) stamps.push_back(o.stamp_s);
  std::sort(stamps.begin(), stamps.end());
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
  std::cerr << std::setprecision(16) << "relations: " << d.matched << " of " << file_time.size()
            << " on scans of the log, offset " << d.offset_s << " s ("
            << (given ? "given" : "detected") << ")\n";
  info->relations_offset_s = d.offset_s;
  info->relations_offset_detected = !given;
  info->relations_in_file = static_cast<std::int64_t>(file_time.size());
  return lifelong::io::ShiftRelations(file_time, d.offset_s);
}

int Replay(const std::string& log, const std::string& out, const std::string& modes,
           const std::string& config_path, const std::string& relations, bool offset_given,
           double offset, const std::string& command_line) {
  lifelong::eval::ExperimentConfig config =
      ExperimentSettings(out, modes, config_path, command_line);
  const lifelong::io::CarmenLog data = lifelong::io::ReadCarmenLog(log);
  std::cerr << "read " << data.observations.size() << " scans from " << log
            << (data.odometry_recovered ? " (raw odometry recovered from a corrected log)" : "")
            << "\n";
  if (data.observations.empty()) throw InputError(log, 0, "", "the log holds no laser scans");
  lifelong::eval::LogInfo info;
  info.scans = static_cast<std::int64_t>(data.observations.size());
  info.backward_stamps = data.backward_scan_stamps;
  if (data.backward_scan_stamps > 0) {
    std::cerr << "warning: " << data.backward_scan_stamps
              << " scans are stamped earlier than the scan before them (first: " << log << ":"
              << data.first_backward_scan_line << "); they are replayed in file order\n";
  }
  if (!relations.empty())
    config.relations = LoadRelations(relations, offset_given, offset, data, &info);
  config.source = log;
  config.log = info;
  PrintResult(lifelong::eval::RunExperiment(data.observations, std::nullopt, config), out);
  return 0;
}

int OptimizeGraph(const std::string& in, const std::string& out, const std::string& method,
                  const std::string& solver, bool no_init) {
  lifelong::slam::OptimizerParams params;
  if (!lifelong::slam::ParseOptimizerMethod(method, &params.method)) {
    throw InputError("--method", 0, method, "unknown method (known: lm, gn)");
  }
  if (solver == "simplicial") {
    params.linear_solver = lifelong::slam::LinearSolver::kSimplicial;
  } else if (solver == "supernodal") {
    params.linear_solver = lifelong::slam::LinearSolver::kSupernodal;
  } else if (solver != "auto") {
    throw InputError("--solver", 0, solver, "unknown solver (known: auto, simplicial, supernodal)");
  }
  params.linear_initialization = !no_init;
  lifelong::io::GraphFile file = lifelong::io::ReadGraphFile(in);
  if (file.graph.NumNodes() == 0) throw InputError(in, 0, "", "the graph has no vertices");
  const auto summary = lifelong::slam::Optimize(file.graph, &file.values, params);
  std::cout << std::setprecision(10) << "vertices " << file.graph.NumNodes() << "\nedges "
            << file.graph.edges().size() << "\ninitial_chi2 " << summary.initial_chi2
            << "\nfinal_chi2 " << summary.final_chi2 << "\niterations " << summary.iterations
            << "\nsolve_time_s " << summary.solve_time_s << "\nconverged "
            << (summary.converged ? "yes" : "no") << " (" << summary.message << ")\n";
  if (!out.empty()) lifelong::io::WriteG2o(out, file.graph, file.values);
  return 0;
}

// The first word that is not an option must be a command; CLI11 alone would call an
// unknown one an "extra argument".
std::optional<std::string> UnknownCommand(int argc, char** argv, const CLI::App& app) {
  if (argc < 2 || argv[1][0] == '-') return std::nullopt;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == argv[1]) return std::nullopt;
  }
  return std::string(argv[1]);
}

// An integer range that names its bounds readably (CLI::PositiveNumber prints the largest
// double as a 300-digit number).
CLI::Validator IntRange(int lo, int hi) {
  return CLI::Validator(
      [lo, hi](std::string& v) {
        int x = 0;
        if (!CLI::detail::lexical_cast(v, x) || x < lo || x > hi) {
          return "must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                 ", got " + v;
        }
        return std::string();
      },
      "INT in [" + std::to_string(lo) + ".." + std::to_string(hi) + "]");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lifelong: a testbed for life-long graph-based 2D laser SLAM"};
  app.require_subcommand(1);
  app.option_defaults()->always_capture_default();
  const std::string command_line = CommandLine(argc, argv);

  std::string scenario = kDefaultScenario, out = "runs/latest", modes = "standard,pruned";
  auto* run = app.add_subcommand("run", "simulate a scenario, map it with every mode, evaluate");
  run->add_option("scenario", scenario, "scenario YAML");
  run->add_option("-o,--out", out, "output directory (replaced only when the run is complete)");
  run->add_option("--modes", modes, "comma-separated: standard,pruned,pruned-exact,pruned-naive");
  std::string config_path;
  run->add_option("--config", config_path, "mapper settings, YAML (see configs/default.yaml)");
  VideoArgs video;
  run->add_option("--video", video.video, "write a video of the run (mp4)");
  run->add_option("--frames", video.frames, "write PNG frames of the run into this directory");
  run->add_option("--stride", video.stride, "render every this many scans")
      ->check(IntRange(1, 1000000));

  std::string sim_scenario, sim_out;
  auto* simulate = app.add_subcommand("simulate", "simulate a scenario into a CARMEN log");
  simulate->add_option("scenario", sim_scenario, "scenario YAML")->required();
  simulate->add_option("-o,--out", sim_out, "output log (.clf or .clf.gz)")->required();

  std::string log, replay_out = "runs/replay", replay_modes = "standard,pruned", relations;
  double offset = 0.0;
  auto* replay = app.add_subcommand("replay", "run the mapper on a CARMEN log");
  replay->add_option("log", log, "CARMEN log, plain or gzipped")->required();
  replay->add_option("-o,--out", replay_out,
                     "output directory (replaced only when the run is complete)");
  replay->add_option("--modes", replay_modes, "comma-separated modes");
  replay->add_option("--config", config_path, "mapper settings, YAML (see configs/default.yaml)");
  replay->add_option("--relations", relations, "relations file (Kuemmerle et al. 2009)");
  auto* offset_option = replay->add_option(
      "--relations-offset", offset,
      "s, relation time = log time + this (default: detected, the offset that puts relation "
      "stamps on scan stamps)");

  std::string graph_in, graph_out;
  auto* optimize = app.add_subcommand("optimize", "optimize a g2o or TORO pose graph");
  optimize->add_option("graph", graph_in, "g2o or TORO file")->required();
  optimize->add_option("-o,--out", graph_out, "write the optimized graph (g2o)");
  std::string method = "lm";
  std::string solver = "auto";
  bool no_init = false;
  optimize->add_option("--method", method, "lm (Levenberg-Marquardt) or gn (Gauss-Newton)");
  optimize->add_option("--solver", solver, "CHOLMOD factorization: auto, simplicial, supernodal");
  optimize->add_flag("--no-init", no_init, "skip the linear (LAGO-style) initialization");

  if (const auto unknown = UnknownCommand(argc, argv, app)) {
    std::cerr << "error: unknown command " << *unknown
              << " (known: run, simulate, replay, optimize; see lifelong --help)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  lifelong::eval::InstallInterruptHandler();
  try {
    if (*run) return Run(scenario, out, modes, config_path, video, command_line);
    if (*simulate) return Simulate(sim_scenario, sim_out);
    if (*replay) {
      return Replay(log, replay_out, replay_modes, config_path, relations,
                    offset_option->count() > 0, offset, command_line);
    }
    if (*optimize) return OptimizeGraph(graph_in, graph_out, method, solver, no_init);
  } catch (const lifelong::eval::Interrupted&) {
    std::cerr << "\ninterrupted: nothing was written; an earlier result is unchanged\n";
    return 130;
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
