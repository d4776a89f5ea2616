// `lifelong reproduce [--profile quick|full] [--book FILE] -o DIR [-j N | --slurm ...]`:
// each experiment of the BOOK runs as a sweep in DIR/<its SPEC's stem>/ (resumed like any
// sweep: cells up to date are not run again), each claim is judged on its sweep's cells, and the
// book is written to DIR/index.html and DIR/results.md (eval/book/book.hpp, docs/reproduce.md).
#include "apps/reproduce_command.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>

#include "apps/exit_codes.hpp"
#include "apps/sweep_command.hpp"
#include "eval/book/book.hpp"
#include "eval/common/interrupt.hpp"
#include "eval/report/build_info.hpp"
#include "eval/sweep/sweep_run.hpp"
#include "eval/sweep/sweep_slurm.hpp"

namespace lifelong::apps {
namespace {

namespace fs = std::filesystem;

std::string Today() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &utc);
  return buf;
}

/// The sweep report's charts of an experiment (each mode's mean and interval per figure),
/// relative to the book's directory.
std::vector<std::string> Charts(const std::string& out, const std::string& dir) {
  std::vector<std::string> charts;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(fs::path(out) / dir, ec)) {
    if (e.path().extension() == ".png") charts.push_back(dir + "/" + e.path().filename().string());
  }
  std::sort(charts.begin(), charts.end());
  return charts;
}

/// The experiment's figures (BookFigure), each from the first finished cell (by name) that
/// has it, relative to the book's directory; a figure no cell has is left out.
std::vector<eval::BookFigure> CellFigures(const std::string& out, const std::string& dir,
                                          const std::vector<eval::BookFigure>& figures) {
  std::vector<std::string> cells;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(fs::path(out) / dir / "cells", ec)) {
    if (fs::exists(e.path() / "sweep_cell.json")) cells.push_back(e.path().filename().string());
  }
  std::sort(cells.begin(), cells.end());
  std::vector<eval::BookFigure> found;
  for (const eval::BookFigure& f : figures) {
    for (const std::string& cell : cells) {
      if (!fs::exists(fs::path(out) / dir / "cells" / cell / f.file)) continue;
      found.push_back({dir + "/cells/" + cell + "/" + f.file, f.seed});
      break;
    }
  }
  return found;
}

eval::SweepOutcome RunExperiment(const ReproduceArgs& a, const eval::SweepOptions& o) {
  if (!a.slurm) return eval::RunSweep(o);
  eval::SlurmOptions slurm;
  slurm.partition = a.partition;
  slurm.time = a.time;
  slurm.sbatch_args = a.sbatch_args;
  return eval::RunSlurmSweep(o, slurm).sweep;
}

int Reproduce(const ReproduceArgs& a) {
  const eval::Book book = eval::LoadBook(a.book);
  fs::create_directories(a.out);
  const eval::BuildInfo build = eval::GetBuildInfo();
  eval::BookOutcome outcome;
  outcome.profile = a.profile;
  outcome.commit = build.commit;
  outcome.day = Today();
  int failed = 0;
  for (const eval::BookExperiment& e : book.experiments) {
    std::cout << "experiment " << e.id << ": " << e.title << "\n";
    eval::ExperimentResult& er = outcome.experiments.emplace_back();
    er.experiment = &e;
    const std::string spec = a.profile == "full" ? e.full_spec : e.quick_spec;
    if (spec.empty()) {
      std::cout << "  not in the " << a.profile << " profile\n";
      continue;
    }
    const std::vector<std::string>& missing =
        a.profile == "full" ? e.full_missing : e.quick_missing;
    if (!missing.empty()) {
      er.not_run =
          "its log is not here: " + missing.front() +
          (missing.size() > 1 ? " (and " + std::to_string(missing.size() - 1) + " more)" : "") +
          (e.get.empty() ? "" : "; get it from " + e.get);
      std::cout << "  not run: " << er.not_run << "\n";
      continue;
    }
    // Experiments that name the same SPEC share its sweep (its cells run once).
    er.dir = fs::path(spec).stem().string();
    const eval::SweepOptions o = SweepOptionsFor(spec, (fs::path(a.out) / er.dir).string(), a.jobs);
    eval::SweepOutcome r = RunExperiment(a, o);
    for (const eval::FailedCell& f : r.failed) {
      std::cout << "  failed: " << f.name << " (exit " << f.exit_code << "), log " << f.log << "\n";
    }
    if (!r.not_started.empty()) std::cout << "  " << eval::NotStartedNote(r) << "\n";
    failed += static_cast<int>(r.failed.size() + r.not_started.size());
    er.tables = std::move(r.tables);
    er.charts = Charts(a.out, er.dir);
    er.figures = CellFigures(a.out, er.dir, e.figures);
    for (const eval::BookClaim& c : e.claims) {
      for (eval::ClaimResult& cr : eval::JudgeClaim(c, er.tables)) {
        std::cout << "  " << c.claim << " [" << eval::SourceName(cr.source)
                  << "]: " << eval::VerdictText(cr.verdict) << " (" << cr.difference.n
                  << " seeds)\n";
        er.claims.push_back(std::move(cr));
      }
    }
  }
  eval::WriteBook(outcome, a.out);
  std::cout << "wrote " << a.out << "/index.html and results.md\n";
  return failed == 0 ? 0 : 1;
}

}  // namespace

int ReproduceCommand(const ReproduceArgs& args) {
  eval::InstallInterruptHandler(3.0);
  return Guarded([&] { return Reproduce(args); },
                 [](const std::exception& e) {
                   return dynamic_cast<const eval::Interrupted*>(&e) != nullptr;
                 });
}

}  // namespace lifelong::apps
