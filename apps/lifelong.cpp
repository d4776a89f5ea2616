// lifelong: the command-line front of the testbed. Thin: parses arguments, runs
// `optimize` itself (slam + io only) and loads liblifelong_commands.so for run, replay,
// simulate and sweep (apps/commands.hpp), so that --help and optimize start without OpenCV or GL.
// Exit codes (apps/exit_codes.hpp): 0 success, 2 bad input or usage, 1 internal failure,
// 130 interrupted.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "apps/commands.hpp"
#include "apps/exit_codes.hpp"
#include "apps/module_loader.hpp"
#include "apps/reproduce_cli.hpp"
#include "apps/sparsify_command.hpp"
#include "io/graph_file.hpp"
#include "io/output_path.hpp"
#include "lifelong_build_info.hpp"  // generated: LIFELONG_VERSION, LIFELONG_COMMIT
#include "sensor/input_error.hpp"
#include "slam/backend/optimizer.hpp"
#include "slam/mapping/mapper_config.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace {

namespace fs = std::filesystem;
using lifelong::InputError;
using lifelong::apps::CommandTable;

constexpr const char* kDefaultScenario = LIFELONG_SOURCE_DIR "/scenarios/corridor_100.yaml";
constexpr const char* kDefaultBook = LIFELONG_SOURCE_DIR "/book/chapter6.yaml";
constexpr const char* kCommandsModule = "liblifelong_commands.so";

std::string CommandLine(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + std::string(argv[i]);
  return s;
}

const CommandTable* LoadCommands() {
  using Entry = const CommandTable* (*)();
  return reinterpret_cast<Entry>(
      lifelong::apps::ModuleEntry(kCommandsModule, lifelong::apps::kCommandTableSymbol))();
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
  if (!std::isfinite(summary.initial_chi2) || !std::isfinite(summary.final_chi2)) {
    std::ostringstream what;
    what << "the graph's chi2 is not finite (initial " << summary.initial_chi2 << ", final "
         << summary.final_chi2 << "): its measurements or information overflow";
    throw InputError(in, 0, "", what.str());
  }
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

// An input file that is a directory is named as such before any work (the readers' streams
// failed on it with a library message, as an internal error).
const CLI::Validator kNotADirectory(
    [](std::string& path) {
      std::error_code ec;
      return std::filesystem::is_directory(path, ec) ? path + " is a directory, not a file"
                                                     : std::string();
    },
    "FILE");

// A path option given as "" names nothing: said at the option, not as "." or a missing file.
const CLI::Validator kNonEmpty(
    [](std::string& v) { return v.empty() ? std::string("the path is empty") : std::string(); },
    "");

// A number that must be given as one: "" (which CLI11 reads as 0), "nan" and "inf" are refused.
const CLI::Validator kFiniteNumber(
    [](std::string& v) {
      double x = 0.0;
      if (v.empty() || !CLI::detail::lexical_cast(v, x) || !std::isfinite(x)) {
        return "expected a finite number, got '" + v + "'";
      }
      return std::string();
    },
    "SECONDS");

// An option that only means something beside another is refused alone, not ignored.
std::optional<std::string> Unused(const CLI::Option* option, const std::string& needs) {
  if (option->count() == 0) return std::nullopt;
  return option->get_name() + " does nothing without " + needs;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lifelong: a testbed for life-long graph-based 2D laser SLAM"};
  app.require_subcommand(1);
  app.option_defaults()->always_capture_default();
  app.set_version_flag("--version", "lifelong " LIFELONG_VERSION " (commit " LIFELONG_COMMIT ")");
  const std::string command_line = CommandLine(argc, argv);

  lifelong::apps::RunArgs run_args;
  run_args.scenario = kDefaultScenario;
  run_args.out = "runs/latest";
  run_args.modes = "standard,pruned";
  run_args.command_line = command_line;
  auto* run = app.add_subcommand("run", "simulate a scenario, map it with every mode, evaluate");
  run->add_option("scenario", run_args.scenario, "scenario YAML")->check(kNotADirectory);
  run->add_option("-o,--out", run_args.out,
                  "output directory (replaced only when the run is complete)")
      ->check(kNonEmpty);
  run->add_option(
      "--modes", run_args.modes,
      "comma-separated, of " + lifelong::slam::ModeList() + "; the first is the baseline");
  run->add_option("--config", run_args.config, "mapper settings, YAML (see configs/default.yaml)")
      ->check(kNotADirectory);
  run->add_option("--present-at", run_args.present_at,
                  "s, comma-separated: also score each mode's map of the present at these times")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  run->add_option("--video", run_args.video, "write a video of the run (mp4)")->check(kNonEmpty);
  run->add_option("--frames", run_args.frames, "write PNG frames of the run into this directory")
      ->check(kNonEmpty);
  auto* stride_option = run->add_option("--stride", run_args.stride, "render every this many scans")
                            ->check(IntRange(1, 1000000));

  lifelong::apps::SimulateArgs sim_args;
  auto* simulate = app.add_subcommand("simulate", "simulate a scenario into a CARMEN log");
  simulate->add_option("scenario", sim_args.scenario, "scenario YAML")
      ->required()
      ->check(kNotADirectory);
  simulate->add_option("-o,--out", sim_args.out, "output log (.clf or .clf.gz)")
      ->required()
      ->check(kNonEmpty);

  lifelong::apps::ReplayArgs replay_args;
  replay_args.out = "runs/replay";
  replay_args.modes = "standard,pruned";
  replay_args.command_line = command_line;
  auto* replay = app.add_subcommand("replay", "run the mapper on a CARMEN log");
  replay->add_option("log", replay_args.log, "CARMEN log, plain or gzipped")
      ->required()
      ->check(kNotADirectory);
  replay
      ->add_option("-o,--out", replay_args.out,
                   "output directory (replaced only when the run is complete)")
      ->check(kNonEmpty);
  replay->add_option("--modes", replay_args.modes,
                     "comma-separated modes; the first is the baseline");
  replay
      ->add_option("--config", replay_args.config,
                   "mapper settings, YAML (see configs/default.yaml)")
      ->check(kNotADirectory);
  auto* relations_option = replay
                               ->add_option("--relations", replay_args.relations,
                                            "relations file (Kuemmerle et al. 2009)")
                               ->check(kNonEmpty & kNotADirectory);
  replay
      ->add_option("--reference", replay_args.reference,
                   "reference trajectory for ATE and RPE at 1 m: TUM or `t x y theta` lines")
      ->check(kNonEmpty & kNotADirectory)
      ->default_str("a corrected log's own FLASER poses, else none");
  auto* offset_option = replay
                            ->add_option("--relations-offset", replay_args.offset_s,
                                         "s, relation time = log time + this (default: detected, "
                                         "the offset that puts relation "
                                         "stamps on scan stamps)")
                            ->check(kFiniteNumber)
                            ->default_str("detected");

  lifelong::apps::ReproduceArgs reproduce_args;
  auto* reproduce = lifelong::apps::AddReproduceCommand(app, &reproduce_args, kDefaultBook);

  lifelong::apps::SweepArgs sweep_args;
  std::string collect_dir;
  auto* sweep = app.add_subcommand(
      "sweep", "map scenarios/logs x seeds x settings, one run per cell, then collect");
  sweep->add_option("spec", sweep_args.spec, "sweep SPEC, YAML (docs/sweeps.md)")
      ->check(kNotADirectory);
  sweep->add_option("-o,--out", sweep_args.out,
                    "sweep directory (cells, runs.csv, aggregate.csv, paired.csv, report.html)");
  sweep->add_option("-j,--jobs", sweep_args.jobs, "cells run at once")
      ->check(IntRange(1, 4096))
      ->default_str("the number of cores");
  sweep->add_flag("--slurm", sweep_args.slurm,
                  "run the cells as a Slurm job array (sbatch), wait for it, then collect");
  sweep->add_option("--partition", sweep_args.partition, "--slurm: the partition")
      ->default_str("the cluster's default");
  sweep->add_option("--time", sweep_args.time, "--slurm: time limit per cell, HH:MM:SS")
      ->default_str("the partition's");
  sweep
      ->add_option("--sbatch-arg", sweep_args.sbatch_args,
                   "--slurm: one more #SBATCH option, as --sbatch-arg=--mem=2G (repeatable)")
      ->allow_extra_args(false);
  sweep->add_flag("--no-wait", sweep_args.no_wait,
                  "--slurm: submit, print the job id and return (collect later)");
  auto* run_cell = sweep->add_subcommand("run-cell", "one cell of DIR/sweep.json (a Slurm task)");
  run_cell->group("");  // hidden: what sweep.sbatch runs
  run_cell->add_option("dir", sweep_args.run_cell_dir, "sweep directory")->required();
  run_cell->add_option("index", sweep_args.run_cell_index, "cell index in DIR/sweep.json")
      ->required();
  auto* collect = sweep->add_subcommand(
      "collect", "collect a sweep directory again: CSVs and report.html from its cells");
  collect->add_option("dir", collect_dir, "sweep directory")->required();

  std::string graph_in, graph_out;
  auto* optimize = app.add_subcommand("optimize", "optimize a g2o or TORO pose graph");
  optimize->add_option("graph", graph_in, "g2o or TORO file")->required()->check(kNotADirectory);
  optimize->add_option("-o,--out", graph_out, "write the optimized graph (g2o)")->check(kNonEmpty);
  std::string method = "lm";
  std::string solver = "auto";
  bool no_init = false;
  optimize->add_option("--method", method, "lm (Levenberg-Marquardt) or gn (Gauss-Newton)");
  optimize->add_option("--solver", solver, "CHOLMOD factorization: auto, simplicial, supernodal");
  optimize->add_flag("--no-init", no_init, "skip the linear (LAGO-style) initialization");

  lifelong::apps::SparsifyArgs sparsify_args;
  sparsify_args.method = "chow-liu";
  auto* sparsify = app.add_subcommand(
      "sparsify", "remove nodes from an optimized pose graph and report the global KL divergence");
  sparsify->add_option("graph", sparsify_args.graph, "g2o or TORO file")
      ->required()
      ->check(kNotADirectory);
  sparsify->add_option("-o,--out", sparsify_args.out, "write the sparsified graph (g2o)")
      ->check(kNonEmpty);
  std::string sparsifier_names;  // the registry's, so a new method shows up by itself
  for (const std::string& name : lifelong::slam::SparsifierNames()) {
    sparsifier_names += (sparsifier_names.empty() ? "" : ", ") + name;
  }
  sparsify->add_option("--method", sparsify_args.method,
                       "what replaces a clique: " + sparsifier_names);
  auto* keep_option = sparsify->add_option("--keep-share", sparsify_args.keep_share,
                                           "keep this share of the nodes, evenly by id");
  sparsify->add_option("--remove", sparsify_args.remove, "file of node ids to remove")
      ->excludes(keep_option)
      ->check(kNotADirectory);
  auto* chords_option =
      sparsify
          ->add_option("--nfr-chords", sparsify_args.nfr_chords,
                       "nfr-subgraph's edges beyond the tree: joined (pairs joined by edges "
                       "before the removal) or mi (the strongest pairs by mutual information)")
          ->capture_default_str();
  auto* means_option =
      sparsify
          ->add_option("--means", sparsify_args.means,
                       "where the new factors' measurements put their minimum: estimate (the "
                       "optimum itself), gradient (keep the exact marginal's gradient there) or "
                       "marginal_mean (at the exact marginal's mean)")
          ->capture_default_str();
  sparsify
      ->add_flag("--zero-residual", sparsify_args.zero_residual,
                 "the same as --means estimate: new factors measure the optimum itself")
      ->excludes(means_option);
  sparsify->add_flag("--no-blanket", sparsify_args.no_blanket,
                     "chow-liu, glc, glc-dense, nfr-*: replace only the factors at the removed "
                     "node and keep those among its neighbours as they are");

  lifelong::apps::ScoreArgs score_args;
  score_args.command_line = command_line;
  auto* score = app.add_subcommand(
      "score", "score any system's trajectory (and map) on a run or a log with our metrics");
  score
      ->add_option("--truth", score_args.truth,
                   "a run's directory, a truth directory, a simulated log, or a corrected log")
      ->required();
  score->add_option("--trajectory", score_args.trajectories, "TUM or `t x y theta` (repeatable)")
      ->required();
  score->add_option("--map", score_args.maps, "its map, PGM + YAML (map_server): one per system");
  score->add_option("--name", score_args.names, "its name (default: the file's stem)");
  score->add_option("-o,--out", score_args.out, "output directory")->required()->check(kNonEmpty);

  if (const auto unknown = UnknownCommand(argc, argv, app)) {
    std::cerr << "error: unknown command " << *unknown
              << " (known: run, simulate, replay, score, optimize, sparsify, sweep, reproduce; see "
                 "lifelong "
                 "--help)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  std::optional<std::string> unused;
  if (*run && run_args.video.empty() && run_args.frames.empty()) {
    unused = Unused(stride_option, "--video or --frames");
  }
  if (*replay && relations_option->count() == 0) {
    unused = Unused(offset_option, "--relations");
  }
  if (*sparsify && sparsify_args.method != "nfr-subgraph") {
    unused = Unused(chords_option, "--method nfr-subgraph");
  }
  if (unused) {
    std::cerr << "error: " << *unused << "\n";
    return 2;
  }
  if (*reproduce && !lifelong::apps::ReproduceArgsProblem(reproduce_args).empty()) {
    std::cerr << "error: " << lifelong::apps::ReproduceArgsProblem(reproduce_args) << "\n";
    return 2;
  }
  const bool slurm_only = !sweep_args.partition.empty() || !sweep_args.time.empty() ||
                          !sweep_args.sbatch_args.empty() || sweep_args.no_wait;
  if (*sweep && !sweep_args.slurm && slurm_only) {
    std::cerr << "error: --partition, --time, --sbatch-arg and --no-wait need --slurm\n";
    return 2;
  }
  if (*sweep && *run_cell) {
  } else if (*sweep && *collect) {
    sweep_args.collect_only = true;
    sweep_args.out = collect_dir;
  } else if (*sweep && (sweep_args.spec.empty() || sweep_args.out.empty())) {
    std::cerr << "error: sweep needs a SPEC and -o DIR (lifelong sweep SPEC.yaml -o DIR), or "
                 "`lifelong sweep collect DIR`\n";
    return 2;
  }
  const auto never_interrupted = [](const std::exception&) { return false; };
  if (*optimize) {
    return lifelong::apps::Guarded(
        [&] {
          if (!graph_out.empty()) lifelong::io::CheckWritableFile(graph_out, "-o");
          return OptimizeGraph(graph_in, graph_out, method, solver, no_init);
        },
        never_interrupted);
  }
  if (*sparsify) {
    return lifelong::apps::Guarded([&] { return lifelong::apps::Sparsify(sparsify_args); },
                                   never_interrupted);
  }
  const CommandTable* commands = nullptr;
  const int loaded = lifelong::apps::Guarded(
      [&] {
        commands = LoadCommands();
        return 0;
      },
      never_interrupted);
  if (loaded != 0) return loaded;
  if (*run) return commands->run(run_args);
  if (*simulate) return commands->simulate(sim_args);
  if (*sweep) return commands->sweep(sweep_args);
  if (*score) return commands->score(score_args);
  if (*reproduce) return commands->reproduce(reproduce_args);
  if (*replay) {
    replay_args.offset_given = offset_option->count() > 0;
    return commands->replay(replay_args);
  }
  return 2;
}
