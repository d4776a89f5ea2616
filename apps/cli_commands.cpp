#include "apps/cli_commands.hpp"

#include "apps/cli_checks.hpp"
#include "apps/reproduce_cli.hpp"
#include "slam/mapping/mode.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::apps {
namespace {

const char kConfigHelp[] = "mapper settings, YAML (see configs/default.yaml)";
const char kOutHelp[] = "output directory (replaced only when the run is complete)";

CLI::App* AddRun(CLI::App& app, RunArgs* a, CLI::Option** stride) {
  auto* run = app.add_subcommand("run", "simulate a scenario, map it with every mode, evaluate");
  run->add_option("scenario", a->scenario, "scenario YAML")->check(NotADirectory());
  run->add_option("-o,--out", a->out, kOutHelp)->check(NonEmpty());
  run->add_option("--modes", a->modes,
                  "comma-separated, of " + slam::ModeList() + "; the first is the baseline");
  run->add_option("--config", a->config, kConfigHelp)->check(NotADirectory());
  run->add_option("--present-at", a->present_at,
                  "s, comma-separated: also score each mode's map of the present at these times")
      ->delimiter(',')
      ->check(CLI::PositiveNumber);
  run->add_option("--video", a->video, "write a video of the run (mp4)")->check(NonEmpty());
  run->add_option("--frames", a->frames, "write PNG frames of the run into this directory")
      ->check(NonEmpty());
  *stride = run->add_option("--stride", a->stride, "render every this many scans")
                ->check(IntRange(1, 1000000));
  run->add_option("--seed", a->seed, "simulate with this seed instead of the scenario's")
      ->check(CLI::NonNegativeNumber)
      ->default_str("the scenario's `seed`");
  return run;
}

CLI::App* AddSimulate(CLI::App& app, SimulateArgs* a) {
  auto* simulate = app.add_subcommand("simulate", "simulate a scenario into a CARMEN log");
  simulate->add_option("scenario", a->scenario, "scenario YAML")
      ->required()
      ->check(NotADirectory());
  simulate->add_option("-o,--out", a->out, "output log (.clf or .clf.gz)")
      ->required()
      ->check(NonEmpty());
  return simulate;
}

CLI::App* AddReplay(CLI::App& app, ReplayArgs* a, CliCommands* c) {
  auto* replay = app.add_subcommand("replay", "run the mapper on a CARMEN log");
  replay->add_option("log", a->log, "CARMEN log, plain or gzipped")
      ->required()
      ->check(NotADirectory());
  replay->add_option("-o,--out", a->out, kOutHelp)->check(NonEmpty());
  replay->add_option("--modes", a->modes, "comma-separated modes; the first is the baseline");
  replay->add_option("--config", a->config, kConfigHelp)->check(NotADirectory());
  c->relations =
      replay->add_option("--relations", a->relations, "relations file (Kuemmerle et al. 2009)")
          ->check(NonEmpty() & NotADirectory());
  replay
      ->add_option("--reference", a->reference,
                   "reference trajectory for ATE and RPE at 1 m: TUM or `t x y theta` lines")
      ->check(NonEmpty() & NotADirectory())
      ->default_str("a corrected log's own FLASER poses, else none");
  c->offset = replay
                  ->add_option("--relations-offset", a->offset_s,
                               "s, relation time = log time + this (default: detected, the "
                               "offset that puts relation stamps on scan stamps)")
                  ->check(FiniteNumber())
                  ->default_str("detected");
  replay
      ->add_option("--seed", a->seed,
                   "replay a draw of the log: each odometry step perturbed by about 1 % "
                   "(docs/cli.md), from this seed")
      ->check(CLI::NonNegativeNumber)
      ->default_str("none: the log as recorded");
  return replay;
}

CLI::App* AddSweep(CLI::App& app, CliArgs* args, CliCommands* c) {
  SweepArgs* a = &args->sweep;
  auto* sweep = app.add_subcommand(
      "sweep", "map scenarios/logs x seeds x settings, one run per cell, then collect");
  sweep->add_option("spec", a->spec, "sweep SPEC, YAML (docs/sweeps.md)")->check(NotADirectory());
  sweep->add_option("-o,--out", a->out,
                    "sweep directory (cells, runs.csv, aggregate.csv, paired.csv, report.html)");
  sweep->add_option("-j,--jobs", a->jobs, "cells run at once")
      ->check(IntRange(1, 4096))
      ->default_str("the number of cores");
  sweep->add_flag("--slurm", a->slurm,
                  "run the cells as a Slurm job array (sbatch), wait for it, then collect");
  sweep->add_option("--partition", a->partition, "--slurm: the partition")
      ->default_str("the cluster's default");
  sweep->add_option("--time", a->time, "--slurm: time limit per cell, HH:MM:SS")
      ->default_str("the partition's");
  sweep
      ->add_option("--sbatch-arg", a->sbatch_args,
                   "--slurm: one more #SBATCH option, as --sbatch-arg=--mem=2G (repeatable)")
      ->allow_extra_args(false);
  sweep->add_flag("--no-wait", a->no_wait,
                  "--slurm: submit, print the job id and return (collect later)");
  c->run_cell = sweep->add_subcommand("run-cell", "one cell of DIR/sweep.json (a Slurm task)");
  c->run_cell->group("");  // hidden: what sweep.sbatch runs
  c->run_cell->add_option("dir", a->run_cell_dir, "sweep directory")->required();
  c->run_cell->add_option("index", a->run_cell_index, "cell index in DIR/sweep.json")->required();
  c->collect = sweep->add_subcommand(
      "collect", "collect a sweep directory again: CSVs and report.html from its cells");
  c->collect->add_option("dir", args->collect_dir, "sweep directory")->required();
  return sweep;
}

CLI::App* AddOptimize(CLI::App& app, OptimizeArgs* a) {
  auto* optimize = app.add_subcommand("optimize", "optimize a g2o or TORO pose graph");
  optimize->add_option("graph", a->graph, "g2o or TORO file")->required()->check(NotADirectory());
  optimize->add_option("-o,--out", a->out, "write the optimized graph (g2o)")->check(NonEmpty());
  optimize->add_option("--method", a->method, "lm (Levenberg-Marquardt) or gn (Gauss-Newton)");
  optimize->add_option("--solver", a->solver,
                       "CHOLMOD factorization: auto, simplicial, supernodal");
  optimize->add_flag("--no-init", a->no_init, "skip the linear (LAGO-style) initialization");
  return optimize;
}

CLI::App* AddSparsify(CLI::App& app, SparsifyArgs* a, CLI::Option** chords) {
  auto* sparsify = app.add_subcommand(
      "sparsify", "remove nodes from an optimized pose graph and report the global KL divergence");
  sparsify->add_option("graph", a->graph, "g2o or TORO file")->required()->check(NotADirectory());
  sparsify->add_option("-o,--out", a->out, "write the sparsified graph (g2o)")->check(NonEmpty());
  std::string names;  // the registry's, so a new method shows up by itself
  for (const std::string& name : slam::SparsifierNames())
    names += (names.empty() ? "" : ", ") + name;
  sparsify->add_option("--method", a->method, "what replaces a clique: " + names);
  auto* keep = sparsify->add_option("--keep-share", a->keep_share,
                                    "keep this share of the nodes, evenly by id");
  sparsify->add_option("--remove", a->remove, "file of node ids to remove")
      ->excludes(keep)
      ->check(NotADirectory());
  *chords = sparsify
                ->add_option("--nfr-chords", a->nfr_chords,
                             "nfr-subgraph's edges beyond the tree: joined (pairs joined by "
                             "edges before the removal) or mi (the strongest pairs by mutual "
                             "information)")
                ->capture_default_str();
  auto* means = sparsify
                    ->add_option("--means", a->means,
                                 "where the new factors' measurements put their minimum: "
                                 "estimate (the optimum itself), gradient (keep the exact "
                                 "marginal's gradient there) or marginal_mean (at the exact "
                                 "marginal's mean)")
                    ->capture_default_str();
  sparsify
      ->add_flag("--zero-residual", a->zero_residual,
                 "the same as --means estimate: new factors measure the optimum itself")
      ->excludes(means);
  sparsify->add_flag("--no-blanket", a->no_blanket,
                     "chow-liu, glc, glc-dense, nfr-*: replace only the factors at the removed "
                     "node and keep those among its neighbours as they are");
  return sparsify;
}

CLI::App* AddScore(CLI::App& app, ScoreArgs* a) {
  auto* score = app.add_subcommand(
      "score", "score any system's trajectory (and map) on a run or a log with our metrics");
  score
      ->add_option("--truth", a->truth,
                   "a run's directory, a truth directory, a simulated log, or a corrected log")
      ->required();
  score->add_option("--trajectory", a->trajectories, "TUM or `t x y theta` (repeatable)")
      ->required();
  score->add_option("--map", a->maps, "its map, PGM + YAML (map_server): one per system");
  score->add_option("--name", a->names, "its name (default: the file's stem)");
  score
      ->add_option("--scenario", a->scenario,
                   "the scenario that made a simulated --truth log: also change_recall and "
                   "stale_seen_cells")
      ->check(NotADirectory());
  score->add_option("-o,--out", a->out, "output directory")->required()->check(NonEmpty());
  return score;
}

}  // namespace

CliCommands AddCommands(CLI::App& app, CliArgs* args, const std::string& command_line,
                        const std::string& default_scenario, const std::string& default_book) {
  args->run.scenario = default_scenario;
  args->run.out = "runs/latest";
  args->run.modes = "standard,pruned";
  args->run.command_line = command_line;
  args->replay.out = "runs/replay";
  args->replay.modes = "standard,pruned";
  args->replay.command_line = command_line;
  args->sparsify.method = "chow-liu";
  args->score.command_line = command_line;
  CliCommands c{};
  c.run = AddRun(app, &args->run, &c.stride);
  c.simulate = AddSimulate(app, &args->simulate);
  c.replay = AddReplay(app, &args->replay, &c);
  c.reproduce = AddReproduceCommand(app, &args->reproduce, default_book);
  c.sweep = AddSweep(app, args, &c);
  c.optimize = AddOptimize(app, &args->optimize);
  c.sparsify = AddSparsify(app, &args->sparsify, &c.chords);
  c.score = AddScore(app, &args->score);
  return c;
}

std::optional<std::string> UsageProblem(const CliCommands& c, CliArgs* args) {
  std::optional<std::string> unused;
  if (*c.run && args->run.video.empty() && args->run.frames.empty()) {
    unused = Unused(c.stride, "--video or --frames");
  }
  if (*c.replay && c.relations->count() == 0) unused = Unused(c.offset, "--relations");
  if (*c.sparsify && args->sparsify.method != "nfr-subgraph") {
    unused = Unused(c.chords, "--method nfr-subgraph");
  }
  if (unused) return unused;
  if (*c.reproduce && !ReproduceArgsProblem(args->reproduce).empty()) {
    return ReproduceArgsProblem(args->reproduce);
  }
  SweepArgs& s = args->sweep;
  const bool slurm_only =
      !s.partition.empty() || !s.time.empty() || !s.sbatch_args.empty() || s.no_wait;
  if (*c.sweep && !s.slurm && slurm_only) {
    return "--partition, --time, --sbatch-arg and --no-wait need --slurm";
  }
  if (*c.sweep && !*c.run_cell && *c.collect) {
    s.collect_only = true;
    s.out = args->collect_dir;
  } else if (*c.sweep && !*c.run_cell && (s.spec.empty() || s.out.empty())) {
    return "sweep needs a SPEC and -o DIR (lifelong sweep SPEC.yaml -o DIR), or "
           "`lifelong sweep collect DIR`";
  }
  args->replay.offset_given = c.offset->count() > 0;
  return std::nullopt;
}

}  // namespace lifelong::apps
