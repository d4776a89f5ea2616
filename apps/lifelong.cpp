// lifelong: the command-line front of the testbed. Thin: parses arguments and calls eval.
// Exit codes (DESIGN.md): 0 success, 2 bad input or usage, 1 internal failure.
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "eval/experiment.hpp"
#include "eval/mapper_config_file.hpp"
#include "eval/simulation.hpp"
#include "io/carmen_log.hpp"
#include "io/graph_file.hpp"
#include "io/relations.hpp"
#include "sensor/input_error.hpp"
#include "sim/scenario.hpp"
#include "slam/optimizer.hpp"

namespace {

namespace fs = std::filesystem;
using lifelong::InputError;

constexpr const char* kDefaultScenario = LIFELONG_SOURCE_DIR "/scenarios/corridor_100.yaml";

std::vector<lifelong::slam::PruningMode> ParseModes(const std::string& list) {
  std::vector<lifelong::slam::PruningMode> modes;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ',')) {
    lifelong::slam::PruningMode mode;
    if (!lifelong::slam::ParsePruningMode(name, &mode)) {
      throw InputError("--modes", 0, name,
                       "unknown mode (known: standard, pruned, pruned-exact, pruned-naive)");
    }
    modes.push_back(mode);
  }
  if (modes.empty()) throw InputError("--modes", 0, "", "no mode given");
  return modes;
}

// Fails early (exit 2) when the output directory cannot be created or written.
void CheckWritableDir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  const fs::path probe = fs::path(dir) / ".lifelong-write-test";
  std::FILE* f = ec ? nullptr : std::fopen(probe.c_str(), "w");
  if (!f) throw InputError(dir, 0, "-o", "output directory is not writable");
  std::fclose(f);
  fs::remove(probe);
}

std::string CommandLine(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

void PrintSummaryTable(const std::string& json_text) {
  std::cout << lifelong::eval::SummaryTable(json_text);
}

int Simulate(const std::string& scenario_path, const std::string& out) {
  const lifelong::sim::Scenario scenario = lifelong::sim::LoadScenario(scenario_path);
  std::cerr << "simulating " << scenario.name << " (" << scenario.duration_s << " s expected)\n";
  const auto run = lifelong::eval::SimulateScenario(scenario, &std::cerr);
  if (!fs::path(out).parent_path().empty()) CheckWritableDir(fs::path(out).parent_path().string());
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

int Run(const std::string& scenario_path, const std::string& out, const std::string& modes,
        const std::string& config_path, const VideoArgs& video, const std::string& command_line) {
  lifelong::eval::ExperimentConfig config;
  config.mapper = MapperSettings(config_path);
  config.video_path = video.video;
  config.frames_dir = video.frames;
  config.video_stride = video.stride;
  config.modes = ParseModes(modes);
  const lifelong::sim::Scenario scenario = lifelong::sim::LoadScenario(scenario_path);
  CheckWritableDir(out);
  std::cerr << "simulating " << scenario.name << " (" << scenario.duration_s << " s expected)\n";
  const auto run = lifelong::eval::SimulateScenario(scenario, &std::cerr);
  for (const auto& c : run.collisions) {
    std::cerr << "warning: collision at t = " << c.stamp_s << " s with " << c.what << "\n";
  }
  config.out_dir = out;
  config.source = scenario_path;
  config.seed = static_cast<std::int64_t>(scenario.seed);
  config.first_pass_s = lifelong::eval::FirstPassEnd(scenario, run);
  config.command_line = command_line;
  config.progress = &std::cerr;
  lifelong::eval::GroundTruth truth{lifelong::eval::TrueWalls(scenario.world)};
  PrintSummaryTable(lifelong::eval::RunExperiment(run.observations, truth, config));
  std::cout << "wrote " << out << "/summary.json and report.html\n";
  return 0;
}

int Replay(const std::string& log, const std::string& out, const std::string& modes,
           const std::string& config_path, const std::string& relations, double offset,
           const std::string& command_line) {
  lifelong::eval::ExperimentConfig config;
  config.mapper = MapperSettings(config_path);
  config.modes = ParseModes(modes);
  CheckWritableDir(out);
  const lifelong::io::CarmenLog data = lifelong::io::ReadCarmenLog(log);
  std::cerr << "read " << data.observations.size() << " scans from " << log
            << (data.odometry_recovered ? " (raw odometry recovered from a corrected log)" : "")
            << "\n";
  if (data.observations.empty()) throw InputError(log, 0, "", "the log holds no laser scans");
  config.out_dir = out;
  config.source = log;
  config.command_line = command_line;
  config.progress = &std::cerr;
  if (!relations.empty()) {
    config.relations_path = relations;
    config.relations_offset_s = offset;
  }
  PrintSummaryTable(lifelong::eval::RunExperiment(data.observations, std::nullopt, config));
  std::cout << "wrote " << out << "/summary.json and report.html\n";
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
  const auto summary = lifelong::slam::Optimize(file.graph, &file.values, params);
  std::cout << std::setprecision(10) << "vertices " << file.graph.NumNodes() << "\nedges "
            << file.graph.edges().size() << "\ninitial_chi2 " << summary.initial_chi2
            << "\nfinal_chi2 " << summary.final_chi2 << "\niterations " << summary.iterations
            << "\nsolve_time_s " << summary.solve_time_s << "\nconverged "
            << (summary.converged ? "yes" : "no") << " (" << summary.message << ")\n";
  if (!out.empty()) lifelong::io::WriteG2o(out, file.graph, file.values);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lifelong: a testbed for life-long graph-based 2D laser SLAM"};
  app.require_subcommand(1);
  const std::string command_line = CommandLine(argc, argv);

  std::string scenario = kDefaultScenario, out = "runs/latest", modes = "standard,pruned";
  auto* run = app.add_subcommand("run", "simulate a scenario, map it with every mode, evaluate");
  run->add_option("scenario", scenario, "scenario YAML (default: corridor_100)");
  run->add_option("-o,--out", out, "output directory");
  run->add_option("--modes", modes, "comma-separated: standard,pruned,pruned-exact,pruned-naive");
  std::string config_path;
  run->add_option("--config", config_path, "mapper settings, YAML (see configs/default.yaml)");
  VideoArgs video;
  run->add_option("--video", video.video, "write a video of the run (mp4)");
  run->add_option("--frames", video.frames, "write PNG frames of the run into this directory");
  run->add_option("--stride", video.stride, "render every this many scans")
      ->check(CLI::PositiveNumber);

  std::string sim_scenario, sim_out;
  auto* simulate = app.add_subcommand("simulate", "simulate a scenario into a CARMEN log");
  simulate->add_option("scenario", sim_scenario, "scenario YAML")->required();
  simulate->add_option("-o,--out", sim_out, "output log (.clf or .clf.gz)")->required();

  std::string log, replay_out = "runs/replay", replay_modes = "standard", relations;
  double offset = lifelong::io::kIntelRelationsTimeOffsetS;
  auto* replay = app.add_subcommand("replay", "run the mapper on a CARMEN log");
  replay->add_option("log", log, "CARMEN log, plain or gzipped")->required();
  replay->add_option("-o,--out", replay_out, "output directory");
  replay->add_option("--modes", replay_modes, "comma-separated modes");
  replay->add_option("--config", config_path, "mapper settings, YAML (see configs/default.yaml)");
  replay->add_option("--relations", relations, "relations file (Kuemmerle et al. 2009)");
  replay->add_option("--relations-offset", offset,
                     "relation time = log time + this (default: Intel's)");

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

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    if (*run) return Run(scenario, out, modes, config_path, video, command_line);
    if (*simulate) return Simulate(sim_scenario, sim_out);
    if (*replay) {
      return Replay(log, replay_out, replay_modes, config_path, relations, offset, command_line);
    }
    if (*optimize) return OptimizeGraph(graph_in, graph_out, method, solver, no_init);
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
