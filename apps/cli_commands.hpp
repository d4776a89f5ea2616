// The thin program's command line: each command's options, added to one CLI11 app, and the
// checks across options that CLI11 cannot express. lifelong.cpp parses and dispatches.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "apps/commands.hpp"
#include "apps/optimize_command.hpp"
#include "apps/sparsify_command.hpp"

namespace lifelong::apps {

/// Every command's arguments, as parsing fills them.
struct CliArgs {
  RunArgs run;
  SimulateArgs simulate;
  ReplayArgs replay;
  ReproduceArgs reproduce;
  SweepArgs sweep;
  std::string collect_dir;  ///< `sweep collect DIR`
  OptimizeArgs optimize;
  SparsifyArgs sparsify;
  ScoreArgs score;
};

/// The commands (set after parsing: a command converts to true when given) and the options
/// the cross-option checks look at.
struct CliCommands {
  CLI::App *run, *simulate, *replay, *reproduce, *sweep, *run_cell, *collect, *optimize, *sparsify,
      *score;
  CLI::Option *stride, *relations, *offset, *chords;
};

/// Adds every command, in --help's order, with `args` to fill. `command_line` is recorded in
/// the outputs of run, replay and score; the two paths are the shipped default scenario and
/// book.
CliCommands AddCommands(CLI::App& app, CliArgs* args, const std::string& command_line,
                        const std::string& default_scenario, const std::string& default_book);

/// After parsing: the usage error (exit 2) of options that need another, or nothing. Sets
/// what the parsed form implies (sweep collect's directory, replay's given offset).
std::optional<std::string> UsageProblem(const CliCommands& commands, CliArgs* args);

}  // namespace lifelong::apps
