// `lifelong sweep SPEC -o DIR [-j N]` and `lifelong sweep collect DIR` (README "Sweeps").
#include "apps/sweep_command.hpp"

#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <thread>

#include "apps/exit_codes.hpp"
#include "eval/build_info.hpp"
#include "eval/interrupt.hpp"
#include "eval/progress.hpp"
#include "eval/sweep_run.hpp"

namespace lifelong::apps {
namespace {

namespace fs = std::filesystem;

void PrintTables(const eval::SweepTables& t, const std::string& dir) {
  std::cout << "collected " << t.runs.size() << " runs of "
            << t.plan.cells.size() - t.missing.size() << " cells";
  if (!t.missing.empty()) std::cout << " (" << t.missing.size() << " cells without a result)";
  std::cout << "\nwrote " << dir << "/runs.csv, aggregate.csv, paired.csv and report.html\n";
}

int Sweep(const SweepArgs& a) {
  if (a.collect_only) {
    PrintTables(eval::CollectSweep(a.out), a.out);
    return 0;
  }
  eval::SweepOptions o;
  o.spec = a.spec;
  o.out_dir = a.out;
  o.program = fs::read_symlink("/proc/self/exe").string();
  const eval::BuildInfo build = eval::GetBuildInfo();
  o.program_id = build.version + " " + build.commit;
  o.parallel =
      a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.progress = &std::cerr;
  o.terminal = ::isatty(STDERR_FILENO) == 1;
  const eval::SweepOutcome r = eval::RunSweep(o);
  std::cout << "ran " << r.ran << " of " << r.cells << " cells (" << r.up_to_date
            << " up to date) in " << eval::FormatDuration(r.wall_s) << " with -j " << o.parallel
            << "\n";
  PrintTables(r.tables, a.out);
  for (const eval::FailedCell& f : r.failed) {
    std::cout << "failed: " << f.name << " (exit " << f.exit_code << "), log " << f.log << "\n";
  }
  return r.failed.empty() ? 0 : 1;
}

}  // namespace

int SweepCommand(const SweepArgs& args) {
  eval::InstallInterruptHandler();
  return Guarded([&] { return Sweep(args); },
                 [](const std::exception& e) {
                   return dynamic_cast<const eval::Interrupted*>(&e) != nullptr;
                 });
}

}  // namespace lifelong::apps
