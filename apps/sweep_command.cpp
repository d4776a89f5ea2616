// `lifelong sweep SPEC -o DIR [-j N | --slurm ...]`, `lifelong sweep collect DIR` and the
// hidden `lifelong sweep run-cell DIR INDEX` of a Slurm array task (docs/sweeps.md).
#include "apps/sweep_command.hpp"

#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <thread>

#include "apps/exit_codes.hpp"
#include "eval/common/interrupt.hpp"
#include "eval/common/progress.hpp"
#include "eval/report/build_info.hpp"
#include "eval/sweep/sweep_run.hpp"
#include "eval/sweep/sweep_slurm.hpp"

namespace lifelong::apps {
namespace {

namespace fs = std::filesystem;

void PrintTables(const eval::SweepTables& t, const std::string& dir) {
  std::cout << "collected " << t.runs.size() << " runs of "
            << t.plan.cells.size() - t.missing.size() << " cells";
  if (!t.missing.empty()) std::cout << " (" << t.missing.size() << " cells without a result)";
  std::cout << "\nwrote " << dir << "/runs.csv, aggregate.csv, paired.csv and report.html\n";
}

std::string ProgramId() {
  const eval::BuildInfo build = eval::GetBuildInfo();
  return build.version + " " + build.commit;
}

void PrintFailed(const std::vector<eval::FailedCell>& failed) {
  for (const eval::FailedCell& f : failed) {
    std::cout << "failed: " << f.name << " (exit " << f.exit_code << "), log " << f.log << "\n";
  }
}

int SlurmSweep(const SweepArgs& a, const eval::SweepOptions& o) {
  eval::SlurmOptions slurm;
  slurm.partition = a.partition;
  slurm.time = a.time;
  slurm.sbatch_args = a.sbatch_args;
  slurm.wait = !a.no_wait;
  const eval::SlurmSweepOutcome r = eval::RunSlurmSweep(o, slurm);
  if (r.job_id.empty()) {
    std::cout << "all " << r.sweep.cells << " cells up to date: nothing submitted\n";
    if (slurm.wait) PrintTables(r.sweep.tables, a.out);
    return 0;
  }
  std::cout << "submitted slurm job " << r.job_id << ": " << r.submitted << " of " << r.sweep.cells
            << " cells (" << r.sweep.up_to_date << " up to date), script " << r.script << "\n";
  if (!slurm.wait) {
    std::cout << "when it has ended (squeue -j " << r.job_id
              << " lists nothing): lifelong sweep collect " << a.out << "\n";
    return 0;
  }
  std::cout << "ran " << r.sweep.ran << " of " << r.sweep.cells << " cells (" << r.sweep.up_to_date
            << " up to date) in " << eval::FormatDuration(r.sweep.wall_s) << " as slurm job "
            << r.job_id << "\n";
  PrintTables(r.sweep.tables, a.out);
  PrintFailed(r.sweep.failed);
  return r.sweep.failed.empty() ? 0 : 1;
}

int Sweep(const SweepArgs& a) {
  if (!a.run_cell_dir.empty()) {
    return eval::RunSweepCell(a.run_cell_dir, a.run_cell_index, ProgramId(), std::cout);
  }
  if (a.collect_only) {
    PrintTables(eval::CollectSweep(a.out), a.out);
    return 0;
  }
  const eval::SweepOptions o = SweepOptionsFor(a.spec, a.out, a.jobs);
  if (a.slurm) return SlurmSweep(a, o);
  const eval::SweepOutcome r = eval::RunSweep(o);
  std::cout << "ran " << r.ran << " of " << r.cells << " cells (" << r.up_to_date
            << " up to date) in " << eval::FormatDuration(r.wall_s) << " with -j " << o.parallel
            << "\n";
  PrintTables(r.tables, a.out);
  PrintFailed(r.failed);
  if (!r.not_started.empty()) std::cout << eval::NotStartedNote(r) << "\n";
  return r.failed.empty() && r.not_started.empty() ? 0 : 1;
}

}  // namespace

eval::SweepOptions SweepOptionsFor(const std::string& spec, const std::string& out, int jobs) {
  eval::SweepOptions o;
  o.spec = spec;
  o.out_dir = out;
  o.program = fs::read_symlink("/proc/self/exe").string();
  o.program_id = ProgramId();
  o.progress = &std::cerr;
  o.terminal = ::isatty(STDERR_FILENO) == 1;
  o.parallel =
      jobs > 0 ? jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return o;
}

int SweepCommand(const SweepArgs& args) {
  // The cells are told to stop at once and answer within their own 1 s grace; the sweep waits
  // a little longer for them.
  eval::InstallInterruptHandler(3.0);
  return Guarded([&] { return Sweep(args); },
                 [](const std::exception& e) {
                   return dynamic_cast<const eval::Interrupted*>(&e) != nullptr;
                 });
}

}  // namespace lifelong::apps
