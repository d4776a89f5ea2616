#include "eval/sweep/sweep_run.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <ostream>

#include "eval/common/interrupt.hpp"
#include "eval/common/progress.hpp"
#include "eval/sweep/sweep_cells.hpp"
#include "eval/sweep/sweep_pool.hpp"
#include "eval/sweep/sweep_report.hpp"
#include "io/atomic_file.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// DIR is a sweep's (holds sweep.json), or absent, or empty: never someone's home.
void PrepareOutput(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_empty(dir, ec) && !fs::exists(dir / "sweep.json", ec)) {
    throw InputError(dir.string(), 0, "-o", "exists and holds no sweep (no sweep.json)");
  }
  fs::create_directories(dir / "cells", ec);
  if (!ec) fs::create_directories(dir / "inputs", ec);
  if (ec) throw InputError(dir.string(), 0, "-o", "cannot create: " + ec.message());
}

class SweepProgress {
 public:
  SweepProgress(const SweepOptions& o, int total, int up_to_date)
      : out_(o.progress),
        terminal_(o.terminal),
        parallel_(std::max(o.parallel, 1)),
        total_(total),
        up_to_date_(up_to_date),
        to_run_(total - up_to_date) {
    Print();
  }
  /// One more cell ran; `note` (if any) is printed on its own line first.
  void Done(bool failed, double wall_s, const std::string& note) {
    ++ran_;
    cell_s_ += wall_s;
    failed_ += failed ? 1 : 0;
    if (out_ && !note.empty()) *out_ << (terminal_ ? "\r\033[K" : "") << note << "\n";
    Print();
  }
  void Finish() {
    if (out_ && terminal_) *out_ << "\n";
  }
  double elapsed_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  void Print() {
    if (!out_) return;
    const double elapsed = elapsed_s();
    // The mean cell so far, for each cell not yet finished, `parallel_` at a time.
    const double eta = ran_ > 0 ? cell_s_ / ran_ * (to_run_ - ran_) / parallel_ : -1.0;
    *out_ << (terminal_ ? "\r\033[K" : "")
          << SweepProgressLine(up_to_date_ + ran_, total_, up_to_date_, failed_, elapsed, eta)
          << (terminal_ ? "" : "\n") << std::flush;
  }
  std::ostream* out_;
  bool terminal_;
  int parallel_;
  double cell_s_ = 0.0;  // wall time of the cells finished, summed
  int total_, up_to_date_, to_run_, ran_ = 0, failed_ = 0;
  Clock::time_point start_ = Clock::now();
};

}  // namespace

std::string SweepProgressLine(int done, int total, int up_to_date, int failed, double elapsed_s,
                              double eta_s) {
  std::string s = "sweep " + std::to_string(done) + "/" + std::to_string(total) + " cells";
  if (up_to_date > 0) s += " (" + std::to_string(up_to_date) + " up to date)";
  s += ", " + std::to_string(failed) + " failed, elapsed " + FormatDuration(elapsed_s);
  if (done < total) s += ", ETA " + (eta_s >= 0.0 ? FormatDuration(eta_s) : std::string("?"));
  return s;
}

SweepTables CollectSweep(const std::string& dir) {
  SweepTables tables = CollectSweepTables(dir);
  WriteSweepCsvs(tables, dir);
  WriteSweepReport(tables, dir);
  return tables;
}

PreparedSweep PrepareSweep(const SweepOptions& o) {
  const SweepSpec spec = LoadSweepSpec(o.spec);
  PreparedSweep p;
  p.plan = ExpandSweep(spec, o.program_id);
  p.plan.program_id = o.program_id;
  const fs::path dir = fs::absolute(o.out_dir);
  PrepareOutput(dir);
  for (std::size_t i = 0; i < p.plan.cells.size(); ++i) {
    SweepPlanCell& cell = p.plan.cells[i];
    const fs::path inputs = dir / "inputs" / cell.name;
    const fs::path cell_dir = dir / "cells" / cell.name;
    cell.argv = CellCommand(o.program, spec, cell, (inputs / "scenario.yaml").string(),
                            (inputs / "config.yaml").string(), cell_dir.string());
    cell.log = (dir / "cells" / (cell.name + ".run.log")).string();
    if (FinishedCellHash(cell_dir.string()) == cell.hash) {
      ++p.up_to_date;
      continue;
    }
    fs::create_directories(inputs);
    const CellInputs in = MakeCellInputs(spec, cell);
    if (!cell.is_log)
      io::WriteFileAtomically((inputs / "scenario.yaml").string(), in.scenario_yaml);
    io::WriteFileAtomically((inputs / "config.yaml").string(), in.config_yaml);
    p.to_run.push_back(i);
  }
  io::WriteFileAtomically((dir / "sweep.json").string(), SweepPlanToJson(p.plan));
  return p;
}

void StampCell(const std::string& dir, const SweepPlanCell& cell) {
  io::WriteFileAtomically((fs::path(dir) / "cells" / cell.name / kCellStampFile).string(),
                          "{\"hash\": \"" + cell.hash + "\"}\n");
}

int RunSweepCell(const std::string& dir, long index, const std::string& program_id,
                 std::ostream& out) {
  const SweepPlan plan = ReadSweepPlan(dir);
  const std::string where = (fs::path(dir) / "sweep.json").string();
  if (index < 0 || index >= static_cast<long>(plan.cells.size())) {
    throw InputError(where, 0, "cells",
                     "has no cell " + std::to_string(index) + " (it has " +
                         std::to_string(plan.cells.size()) + ")");
  }
  if (plan.program_id != program_id) {
    throw InputError(where, 0, "program_id",
                     "the plan was written by lifelong " + plan.program_id + ", this is " +
                         program_id + ": its hashes would not describe this program's results");
  }
  const SweepPlanCell& cell = plan.cells[static_cast<std::size_t>(index)];
  if (cell.argv.empty()) throw InputError(where, 0, "argv", "cell " + cell.name + " has none");
  if (FinishedCellHash((fs::path(dir) / "cells" / cell.name).string()) == cell.hash) {
    out << "cell " << cell.name << " is up to date\n";
    return 0;
  }
  out << "cell " << cell.name << ": " << cell.argv.front() << " " << cell.argv[1] << " ..., log "
      << cell.log << std::endl;
  PoolOptions pool;
  pool.stop = [] { return InterruptRequested(); };
  const PoolJobResult r = RunProcessPool({{cell.argv, cell.log}}, pool).front();
  ThrowIfInterrupted();
  if (r.exit_code == 0) StampCell(dir, cell);
  out << "cell " << cell.name << " exit " << r.exit_code << " after " << FormatDuration(r.wall_s)
      << "\n";
  return r.exit_code;
}

std::string NotStartedNote(const SweepOutcome& outcome) {
  if (outcome.not_started.empty()) return "";
  const std::size_t n = outcome.not_started.size();
  return "not started: " + std::to_string(n) + (n == 1 ? " cell" : " cells") +
         ", because a cell's program could not be started (exit 127, see its log); once it is "
         "there again, the same command runs " +
         (n == 1 ? "it" : "them") + " and keeps the finished cells";
}

SweepOutcome RunSweep(const SweepOptions& o) {
  const PreparedSweep prepared = PrepareSweep(o);
  const SweepPlan& plan = prepared.plan;
  const fs::path dir(o.out_dir);

  SweepOutcome outcome;
  outcome.cells = static_cast<int>(plan.cells.size());
  outcome.up_to_date = prepared.up_to_date;
  std::vector<PoolJob> jobs;
  for (std::size_t i : prepared.to_run) jobs.push_back({plan.cells[i].argv, plan.cells[i].log});

  SweepProgress progress(o, outcome.cells, outcome.up_to_date);
  PoolOptions pool;
  pool.parallel = o.parallel;
  pool.stop = [] { return InterruptRequested(); };
  pool.on_done = [&](std::size_t i, const PoolJobResult& r) {
    const SweepPlanCell& cell = plan.cells[prepared.to_run[i]];
    ++outcome.ran;
    std::string note;
    if (r.exit_code == 0) {
      StampCell(dir.string(), cell);
    } else {
      outcome.failed.push_back({cell.name, r.exit_code, cell.log});
      note = "cell " + cell.name + " failed (exit " + std::to_string(r.exit_code) + "), see " +
             cell.log;
    }
    progress.Done(r.exit_code != 0, r.wall_s, note);
  };
  const std::vector<PoolJobResult> results = RunProcessPool(jobs, pool);
  progress.Finish();
  ThrowIfInterrupted();
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (!results[i].started) outcome.not_started.push_back(plan.cells[prepared.to_run[i]].name);
  }
  outcome.tables = CollectSweep(dir.string());
  outcome.wall_s = progress.elapsed_s();
  return outcome;
}

}  // namespace lifelong::eval
