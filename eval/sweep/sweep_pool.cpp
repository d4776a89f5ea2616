#include "eval/sweep/sweep_pool.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>

extern char** environ;

namespace lifelong::eval {
namespace {

using Clock = std::chrono::steady_clock;

// Why a job could not start, in its log, where the sweep's failure list points (a program
// rebuilt or removed while the sweep ran lands here).
void WriteStartFailure(const PoolJob& job, int err) {
  const int fd = ::open(job.log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) return;  // the exit code 127 says it failed either way
  const std::string why = "lifelong sweep: cannot start " + job.argv.front() + ": " +
                          std::strerror(err) +
                          " (was the program rebuilt or removed while the sweep ran?)\n";
  const ssize_t written = ::write(fd, why.data(), why.size());
  (void)written;
  ::close(fd);
}

// Starts one job; returns its pid, or -1 with the reason written to its log.
pid_t Spawn(const PoolJob& job) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, job.log_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::vector<char*> argv;
  for (const std::string& a : job.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int err = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err == 0) return pid;
  WriteStartFailure(job, err);
  return -1;
}

int ExitCode(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

}  // namespace

std::vector<PoolJobResult> RunProcessPool(const std::vector<PoolJob>& jobs,
                                          const PoolOptions& options) {
  std::vector<PoolJobResult> results(jobs.size());
  std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
  const std::size_t parallel = static_cast<std::size_t>(std::max(options.parallel, 1));
  const auto finish = [&](std::size_t i) {
    if (options.on_done) options.on_done(i, results[i]);
  };
  std::size_t next = 0;
  bool stopping = false;
  bool cannot_start = false;  // the later jobs would fail alike: none is started
  while (next < jobs.size() || !running.empty()) {
    if (!stopping && options.stop && options.stop()) {
      stopping = true;
      for (const auto& entry : running) ::kill(entry.first, SIGTERM);
    }
    while (!stopping && !cannot_start && next < jobs.size() && running.size() < parallel) {
      const std::size_t i = next++;
      const pid_t pid = Spawn(jobs[i]);
      results[i].started = true;
      if (pid < 0) {
        results[i].exit_code = 127;  // as a shell reports a program it cannot start
        cannot_start = true;
        finish(i);
      } else {
        running[pid] = {i, Clock::now()};
      }
    }
    if ((stopping || cannot_start) && running.empty()) break;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid > 0 && running.count(pid)) {
      const auto [i, start] = running[pid];
      running.erase(pid);
      results[i].exit_code = ExitCode(status);
      results[i].wall_s = std::chrono::duration<double>(Clock::now() - start).count();
      finish(i);
    } else if (pid < 0 && errno == ECHILD && !running.empty()) {
      throw std::runtime_error("sweep: lost track of its child processes");
    } else if (pid <= 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  return results;
}

}  // namespace lifelong::eval
