// `lifelong sweep SPEC -o DIR --slurm`: the cells not up to date as one Slurm job array
// (docs/sweeps.md). DIR/sweep.sbatch holds one array task per such cell; task i runs
// `PROGRAM sweep run-cell DIR CELL_i`, i.e. exactly what the local pool runs (the cell's
// command and log from DIR/sweep.json, the stamp on success). It is submitted with
// `sbatch --parsable`; then, unless told not to wait, `squeue` is polled until every task
// has ended, each ended task's state and exit code are read from `sacct` (or, without
// accounting, `scontrol show job`), and the sweep is collected as after the local pool.
// Paths are absolute: the program, the inputs and DIR must be on a filesystem the nodes share.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "eval/sweep/sweep_run.hpp"

namespace lifelong::eval {

struct SlurmOptions {
  std::string partition;                 ///< empty: the cluster's default
  std::string time;                      ///< HH:MM:SS per task; empty: the partition's
  std::vector<std::string> sbatch_args;  ///< each one `#SBATCH` line, e.g. --mem=2G
  bool wait = true;                      ///< false: submit, print the job id, return
  double poll_s = 2.0;
};

struct SlurmSweepOutcome {
  SweepOutcome sweep;  ///< tables only when waited
  std::string job_id;  ///< empty: nothing was submitted (every cell up to date)
  int submitted = 0;
  std::string script;  ///< DIR/sweep.sbatch
};

/// The job array script: task i runs plan cell `cells[i]` (indices into plan.cells).
std::string SlurmScript(const std::vector<std::size_t>& cells, const std::string& dir,
                        const std::string& program, const SlurmOptions& slurm);

/// Prepares the sweep (PrepareSweep), submits its cells not up to date and, when
/// slurm.wait, waits for them and collects. Throws InputError (bad SPEC, DIR or option),
/// std::runtime_error (sbatch failed), eval::Interrupted (the job is cancelled first).
SlurmSweepOutcome RunSlurmSweep(const SweepOptions& options, const SlurmOptions& slurm);

}  // namespace lifelong::eval
