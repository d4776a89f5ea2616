#include "eval/sweep/sweep_slurm.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <map>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "eval/common/interrupt.hpp"
#include "eval/common/progress.hpp"
#include "io/atomic_file.hpp"
#include "sensor/input_error.hpp"

extern char** environ;

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Captured {
  int exit_code = -1;  ///< -1: could not start
  std::string out;
};

// Runs `argv` (searched on PATH) with stdout captured; stderr too when `with_stderr`,
// else it goes to /dev/null.
Captured Capture(const std::vector<std::string>& argv, bool with_stderr) {
  Captured c;
  int fds[2];
  if (::pipe(fds) != 0) return c;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  if (with_stderr) {
    posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  } else {
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  }
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int err = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  char buf[4096];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof(buf))) != 0;) {
    if (n > 0) c.out.append(buf, static_cast<std::size_t>(n));
    if (n < 0 && errno != EINTR) break;
  }
  ::close(fds[0]);
  if (err != 0) return c;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return c;
}

std::string Quoted(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

// "1:0" (exit code 1) or "0:15" (signal 15) -> 1 or 143.
int SlurmExitCode(const std::string& s) {
  const std::size_t colon = s.find(':');
  try {
    const int code = std::stoi(s.substr(0, colon));
    const int signal = colon == std::string::npos ? 0 : std::stoi(s.substr(colon + 1));
    return code == 0 && signal != 0 ? 128 + signal : code;
  } catch (const std::exception&) {
    return -1;
  }
}

struct TaskEnd {
  std::string state;  ///< COMPLETED, FAILED, CANCELLED, TIMEOUT, ...
  int exit_code = -1;
};

// The ended tasks' states: from sacct when accounting works, else scontrol (which keeps
// ended jobs for MinJobAge, 300 s by default).
std::map<long, TaskEnd> EndedTasks(const std::string& job) {
  std::map<long, TaskEnd> out;
  const Captured acct =
      Capture({"sacct", "-j", job, "-n", "-P", "-o", "JobID,State,ExitCode"}, false);
  std::istringstream lines(acct.exit_code == 0 ? acct.out : "");
  for (std::string line; std::getline(lines, line);) {  // 123_4|COMPLETED|0:0
    std::vector<std::string> f;
    std::istringstream fields(line);
    for (std::string x; std::getline(fields, x, '|');) f.push_back(x);
    if (f.size() < 3 || f[0].rfind(job + "_", 0) != 0) continue;
    const std::string task = f[0].substr(job.size() + 1);
    if (task.empty() || task.find_first_not_of("0123456789") != std::string::npos) continue;
    out[std::stol(task)] = {f[1].substr(0, f[1].find(' ')), SlurmExitCode(f[2])};
  }
  if (!out.empty()) return out;
  const Captured show = Capture({"scontrol", "-o", "show", "job", job}, false);
  std::istringstream records(show.exit_code == 0 ? show.out : "");
  for (std::string line; std::getline(records, line);) {
    std::map<std::string, std::string> kv;
    std::istringstream tokens(line);
    for (std::string t; tokens >> t;) {
      const std::size_t eq = t.find('=');
      if (eq != std::string::npos) kv[t.substr(0, eq)] = t.substr(eq + 1);
    }
    const std::string& task = kv["ArrayTaskId"];
    if (task.empty() || task.find_first_not_of("0123456789") != std::string::npos) continue;
    out[std::stol(task)] = {kv["JobState"], SlurmExitCode(kv["ExitCode"])};
  }
  return out;
}

std::string Submit(const std::string& script) {
  const Captured c = Capture({"sbatch", "--parsable", script}, true);
  std::string id;
  std::istringstream lines(c.out);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty()) id = line.substr(0, line.find(';'));  // "123" or "123;cluster"
  }
  if (c.exit_code != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    throw std::runtime_error(c.exit_code < 0
                                 ? "cannot start sbatch (is Slurm installed and on PATH?)"
                                 : "sbatch " + script + " failed (exit " +
                                       std::to_string(c.exit_code) + "): " + c.out);
  }
  return id;
}

}  // namespace

std::string SlurmScript(const std::vector<std::size_t>& cells, const std::string& dir,
                        const std::string& program, const SlurmOptions& slurm) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by lifelong sweep --slurm: one array task per cell not up to date; task i\n"
    << "# runs cell cells[i] of " << dir << "/sweep.json through `lifelong sweep run-cell`.\n"
    << "#SBATCH --job-name=lifelong-sweep\n"
    << "#SBATCH --array=0-" << cells.size() - 1 << "\n"
    << "#SBATCH --ntasks=1\n"
    << "#SBATCH --output=" << dir << "/cells/slurm-%A_%a.out\n";
  if (!slurm.partition.empty()) s << "#SBATCH --partition=" << slurm.partition << "\n";
  if (!slurm.time.empty()) s << "#SBATCH --time=" << slurm.time << "\n";
  for (const std::string& a : slurm.sbatch_args) s << "#SBATCH " << a << "\n";
  s << "cells=(";
  for (std::size_t i = 0; i < cells.size(); ++i) s << (i ? " " : "") << cells[i];
  s << ")\nexec " << Quoted(program) << " sweep run-cell " << Quoted(dir)
    << " \"${cells[$SLURM_ARRAY_TASK_ID]}\"\n";
  return s.str();
}

namespace {

/// The array job's tasks as squeue reports them: which are active, how many run.
struct QueueState {
  std::set<long> active;
  int running = 0;
};

QueueState ParseQueue(const std::string& squeue_out) {
  QueueState q;
  std::istringstream lines(squeue_out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream f(line);
    long task = -1;
    std::string state;
    if (f >> task >> state) q.active.insert(task);
    q.running += state == "RUNNING" || state == "COMPLETING" ? 1 : 0;
  }
  return q;
}

/// Follows a submitted array job until every task has ended: reports each failed task as it
/// ends (with its log) and a status line, and cancels the job on Ctrl-C.
class JobWatch {
 public:
  JobWatch(const SweepOptions& o, const PreparedSweep& prepared, const std::string& dir,
           SlurmSweepOutcome* r)
      : o_(o),
        prepared_(prepared),
        dir_(dir),
        r_(r),
        tasks_(static_cast<long>(prepared.to_run.size())) {}

  /// One squeue poll; true once every task has ended.
  bool Poll(double elapsed_s) {
    const Captured q = Capture({"squeue", "-j", r_->job_id, "-h", "-r", "-o", "%K %T"}, true);
    if (q.exit_code != 0 && q.out.find("Invalid job id") == std::string::npos) {
      if (++misses_ > 30) throw std::runtime_error("squeue keeps failing: " + q.out);
      return false;
    }
    misses_ = 0;
    const QueueState state = ParseQueue(q.exit_code == 0 ? q.out : "");
    std::vector<long> newly;
    for (long t = 0; t < tasks_; ++t) {
      if (!state.active.count(t) && !reported_.count(t)) newly.push_back(t);
    }
    if (!newly.empty()) Ended(newly);
    PrintStatus(state.running, elapsed_s);
    return static_cast<long>(reported_.size()) == tasks_;
  }

  /// Sleeps poll_s, in steps that notice an interrupt: then cancels the job and throws.
  void Wait(double poll_s) const {
    for (double w = 0.0; w < poll_s; w += 0.05) {
      if (InterruptRequested()) {
        Capture({"scancel", r_->job_id}, true);
        if (o_.progress) *o_.progress << "\ncancelled slurm job " << r_->job_id << "\n";
        ThrowIfInterrupted();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }

 private:
  void Ended(const std::vector<long>& newly) {
    const std::map<long, TaskEnd> ends = EndedTasks(r_->job_id);
    for (long t : newly) {
      const SweepPlanCell& cell =
          prepared_.plan.cells[prepared_.to_run[static_cast<std::size_t>(t)]];
      const auto e = ends.find(t);
      const bool stamped = FinishedCellHash(dir_ + "/cells/" + cell.name) == cell.hash;
      const TaskEnd end = e != ends.end() ? e->second : TaskEnd{stamped ? "COMPLETED" : "?", -1};
      reported_.insert(t);
      ++r_->sweep.ran;
      if (stamped && end.exit_code <= 0 && end.state == "COMPLETED") continue;
      ++failed_;
      r_->sweep.failed.push_back({cell.name, end.exit_code, cell.log});
      if (o_.progress) {
        *o_.progress << (o_.terminal ? "\r\033[K" : "") << "task " << r_->job_id << "_" << t
                     << " (cell " << cell.name << ") " << end.state << " (exit " << end.exit_code
                     << "), see " << cell.log << " and " << dir_ << "/cells/slurm-" << r_->job_id
                     << "_" << t << ".out\n";
      }
    }
  }

  void PrintStatus(int running, double elapsed_s) {
    const long ended = static_cast<long>(reported_.size());
    std::ostringstream line;
    line << "slurm job " << r_->job_id << ": " << ended << "/" << tasks_ << " tasks ended, "
         << failed_ << " failed, " << running << " running, " << (tasks_ - ended - running)
         << " pending";
    if (o_.progress && (o_.terminal || line.str() != last_)) {  // a plain line only on a change
      *o_.progress << (o_.terminal ? "\r\033[K" : "") << line.str() << ", elapsed "
                   << FormatDuration(elapsed_s) << (o_.terminal ? "" : "\n") << std::flush;
    }
    last_ = line.str();
  }

  const SweepOptions& o_;
  const PreparedSweep& prepared_;
  const std::string dir_;
  SlurmSweepOutcome* r_;
  const long tasks_;
  std::set<long> reported_;
  int failed_ = 0, misses_ = 0;
  std::string last_;
};

}  // namespace

SlurmSweepOutcome RunSlurmSweep(const SweepOptions& o, const SlurmOptions& slurm) {
  for (const std::string& a : slurm.sbatch_args) {
    if (a.empty() || a.find('\n') != std::string::npos || a[0] != '-') {
      throw InputError(a, 0, "--sbatch-arg", "must be one sbatch option, e.g. --mem=2G");
    }
  }
  const PreparedSweep prepared = PrepareSweep(o);
  const std::string dir = fs::absolute(o.out_dir).string();
  SlurmSweepOutcome r;
  r.sweep.cells = static_cast<int>(prepared.plan.cells.size());
  r.sweep.up_to_date = prepared.up_to_date;
  r.submitted = static_cast<int>(prepared.to_run.size());
  const Clock::time_point start = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  if (prepared.to_run.empty()) {
    if (slurm.wait) r.sweep.tables = CollectSweep(o.out_dir);
    return r;
  }
  r.script = dir + "/sweep.sbatch";
  io::WriteFileAtomically(r.script, SlurmScript(prepared.to_run, dir, o.program, slurm));
  r.job_id = Submit(r.script);
  if (!slurm.wait) return r;
  if (o.progress) {
    *o.progress << "slurm job " << r.job_id << " submitted: " << prepared.to_run.size()
                << " array tasks, script " << r.script << " (Ctrl-C cancels it)\n";
  }
  JobWatch watch(o, prepared, dir, &r);
  while (!watch.Poll(elapsed())) watch.Wait(slurm.poll_s);
  if (o.progress && o.terminal) *o.progress << "\n";
  r.sweep.tables = CollectSweep(o.out_dir);
  r.sweep.wall_s = elapsed();
  return r;
}

}  // namespace lifelong::eval
