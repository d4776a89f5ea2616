// A local pool of child processes for `lifelong sweep`: at most N at once, each with its
// stdout and stderr in its own log file and stdin from /dev/null. Started with
// posix_spawn (no shell), reaped by polling waitpid, so that an interruption is noticed
// within 50 ms: then no new job starts, the running ones get SIGTERM (they remove their
// staging directories and exit 130) and are waited for. A job whose program cannot be
// started (exit 127, the reason in its log) starts no later job either: they would fail
// alike (a program rebuilt or removed under the sweep); the running ones finish.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace lifelong::eval {

struct PoolJob {
  std::vector<std::string> argv;  ///< argv[0] is the program's path
  std::string log_path;           ///< stdout and stderr, truncated at start
};

struct PoolJobResult {
  bool started = false;
  int exit_code = -1;  ///< the exit status, or 128 + signal; -1: never started
  double wall_s = 0.0;
};

struct PoolOptions {
  int parallel = 1;
  std::function<void(std::size_t job, const PoolJobResult&)> on_done;  ///< may be empty
  std::function<bool()> stop;  ///< polled; true: start nothing more, stop the running jobs
};

/// Runs `jobs`, in order, at most options.parallel at once; returns one result per job
/// (`started` false for those never started).
std::vector<PoolJobResult> RunProcessPool(const std::vector<PoolJob>& jobs,
                                          const PoolOptions& options);

}  // namespace lifelong::eval
