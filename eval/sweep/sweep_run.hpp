// `lifelong sweep SPEC -o DIR [-j N]`: expands the SPEC (eval/sweep/sweep_spec.hpp) into cells
// (eval/sweep/sweep_cells.hpp), runs each cell whose current result is missing as a child
// process of `program` (a local pool, eval/sweep/sweep_pool.hpp), then collects the tables
// and the report (eval/sweep/sweep_collect.hpp, sweep_report.hpp). Layout of DIR:
//   sweep.json                 the plan (cells, settings, hashes)
//   inputs/<cell>/scenario.yaml, config.yaml   what the cell's run was given
//   cells/<cell>/              the run's usual output, + sweep_cell.json when it succeeded
//   cells/<cell>.run.log       the run's stdout and stderr
//   runs.csv, aggregate.csv, paired.csv, report.html, sweep_*.png, plot_data/
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "eval/sweep/sweep_collect.hpp"

namespace lifelong::eval {

struct SweepOptions {
  std::string spec;
  std::string out_dir;
  std::string program;     ///< the lifelong binary each cell runs
  std::string program_id;  ///< its version and commit: part of every cell's hash
  int parallel = 1;
  std::ostream* progress = nullptr;  ///< one line for the sweep; nullptr: quiet
  bool terminal = false;             ///< redraw that line in place
};

struct FailedCell {
  std::string name;
  int exit_code = 0;
  std::string log;  ///< path of its run.log
};

struct SweepOutcome {
  int cells = 0;
  int up_to_date = 0;  ///< not run: their result was there for the same inputs
  int ran = 0;
  std::vector<FailedCell> failed;
  /// Never started: an earlier cell's program could not be started (exit 127), so these
  /// would have failed alike. Running the sweep again once the program is back runs them.
  std::vector<std::string> not_started;
  double wall_s = 0.0;
  SweepTables tables;
};

/// "not started: 4 cells, because ..." for outcome.not_started (empty when there are none).
std::string NotStartedNote(const SweepOutcome& outcome);

/// The plan with every cell's command and log (absolute paths), and the cells to run.
struct PreparedSweep {
  SweepPlan plan;
  std::vector<std::size_t> to_run;  ///< plan cells whose current result is missing
  int up_to_date = 0;
};

/// Checks the SPEC and DIR, writes DIR/sweep.json and the inputs of every cell to run:
/// what both the local pool and a Slurm job array run from. Throws InputError.
PreparedSweep PrepareSweep(const SweepOptions& options);

/// Records that `cell` succeeded: DIR/cells/<name>/sweep_cell.json with its hash.
void StampCell(const std::string& dir, const SweepPlanCell& cell);

/// `lifelong sweep run-cell DIR INDEX` (a Slurm array task): runs plan cell INDEX exactly
/// as the local pool does (its command, its log, the stamp on success); nothing when it
/// is up to date. Refuses a plan written by another program version. Returns the cell's
/// exit code. Throws InputError, eval::Interrupted.
int RunSweepCell(const std::string& dir, long index, const std::string& program_id,
                 std::ostream& out);

/// Checks everything (SPEC, DIR) before any cell runs: InputError then. Throws
/// eval::Interrupted after Ctrl-C/SIGTERM once the running cells have stopped.
SweepOutcome RunSweep(const SweepOptions& options);

/// Collects DIR's tables and writes the CSVs and the report; what `sweep collect` does.
SweepTables CollectSweep(const std::string& dir);

/// "sweep 3/6 cells (1 up to date), 1 failed, elapsed 0:12, ETA 0:08".
std::string SweepProgressLine(int done, int total, int up_to_date, int failed, double elapsed_s,
                              double eta_s);

}  // namespace lifelong::eval
