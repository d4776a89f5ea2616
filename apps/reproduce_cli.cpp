// The command line of `lifelong reproduce` (apps/reproduce_cli.hpp).
#include "apps/reproduce_cli.hpp"

namespace lifelong::apps {

CLI::App* AddReproduceCommand(CLI::App& app, ReproduceArgs* a, const std::string& default_book) {
  a->book = default_book;
  auto* c = app.add_subcommand(
      "reproduce",
      "run the seed's chapter 6 as sweeps and write a results book with a verdict "
      "per claim");
  c->add_option("--profile", a->profile,
                "quick: fewer seeds and shorter scenarios, for one machine; full: for a cluster")
      ->check(CLI::IsMember({"quick", "full"}))
      ->capture_default_str();
  c->add_option("--book", a->book, "BOOK, YAML: experiments and claims (docs/reproduce.md)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  c->add_option("-o,--out", a->out,
                "book directory (index.html, results.md, a sweep per experiment)")
      ->required();
  c->add_option("-j,--jobs", a->jobs, "cells run at once")
      ->check(CLI::Range(1, 4096))
      ->default_str("the number of cores");
  c->add_flag("--slurm", a->slurm, "run each experiment's cells as a Slurm job array, and wait");
  c->add_option("--partition", a->partition, "--slurm: the partition")
      ->default_str("the cluster's default");
  c->add_option("--time", a->time, "--slurm: time limit per cell, HH:MM:SS")
      ->default_str("the partition's");
  c->add_option("--sbatch-arg", a->sbatch_args, "--slurm: one more #SBATCH option (repeatable)")
      ->allow_extra_args(false);
  return c;
}

std::string ReproduceArgsProblem(const ReproduceArgs& a) {
  const bool slurm_only = !a.partition.empty() || !a.time.empty() || !a.sbatch_args.empty();
  if (slurm_only && !a.slurm) return "--partition, --time and --sbatch-arg need --slurm";
  if (a.slurm && a.jobs > 0) return "-j and --slurm exclude each other";
  return "";
}

}  // namespace lifelong::apps
