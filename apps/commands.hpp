// The commands that need the whole testbed (simulator, mapper, evaluation, OpenCV): run,
// replay, simulate and sweep. They live in the module liblifelong_commands.so, which
// `lifelong` loads only when one of them is asked for, so that `lifelong optimize` and
// `--help` start without OpenCV. Offscreen OpenGL is a module of its own, loaded only for a
// video (apps/video_module.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace lifelong::apps {

struct RunArgs {
  std::string scenario, out, modes, config;
  std::string video, frames;         ///< optional outputs; empty: none
  int stride = 20;                   ///< render every this many scans
  std::vector<double> present_at;    ///< s: also score the map of the present at these times
  std::optional<std::int64_t> seed;  ///< --seed: instead of the scenario's own
  std::string command_line;
};

struct SimulateArgs {
  std::string scenario, out;
};

struct ReplayArgs {
  std::string log, out, modes, config, relations;
  /// A reference trajectory (TUM or t x y theta); empty: a corrected log's own poses, if any.
  std::string reference;
  bool offset_given = false;  ///< --relations-offset was given: use offset_s, detect nothing
  double offset_s = 0.0;
  /// --seed: replay a draw of the log (eval/experiment/log_draw.hpp), not the log as recorded.
  std::optional<std::int64_t> seed;
  std::string command_line;
};

/// `sweep SPEC -o DIR [-j N]`, or `sweep collect DIR` (collect_only, out = DIR).
struct SweepArgs {
  std::string spec, out;
  int jobs = 0;  ///< 0: the number of cores
  bool collect_only = false;
  bool slurm = false;  ///< run the cells as a Slurm job array (eval/sweep/sweep_slurm.hpp)
  std::string partition, time;
  std::vector<std::string> sbatch_args;
  bool no_wait = false;
  std::string run_cell_dir;  ///< `sweep run-cell DIR INDEX` (a Slurm task); empty: not
  long run_cell_index = -1;
};

/// `score --truth PATH --trajectory FILE [--map MAP.yaml] [--name NAME] -o OUT`; the last
/// three repeat, one per system (eval/experiment/score.hpp).
struct ScoreArgs {
  std::string truth, out;
  std::string scenario;  ///< the scenario that made a simulated --truth log: change_recall
  std::vector<std::string> trajectories, maps, names;
  std::string command_line;
};

/// `reproduce [--profile quick|full] [--book FILE] -o DIR [-j N | --slurm ...]`
/// (eval/book/book.hpp).
struct ReproduceArgs {
  std::string book, profile = "quick", out;
  int jobs = 0;  ///< 0: the number of cores
  bool slurm = false;
  std::string partition, time;
  std::vector<std::string> sbatch_args;
};

/// Each returns the process exit code (0, 1, 2 or 130) after printing any error.
struct CommandTable {
  int (*run)(const RunArgs&);
  int (*simulate)(const SimulateArgs&);
  int (*replay)(const ReplayArgs&);
  int (*sweep)(const SweepArgs&);          ///< apps/sweep_command.cpp
  int (*score)(const ScoreArgs&);          ///< apps/score_command.cpp
  int (*reproduce)(const ReproduceArgs&);  ///< apps/reproduce_command.cpp
};

/// The module's one exported symbol: `extern "C" const CommandTable* <this>()`.
inline constexpr const char* kCommandTableSymbol = "lifelong_command_table_v5";

}  // namespace lifelong::apps
