// The command line of `lifelong reproduce` (apps/commands.hpp ReproduceArgs), kept out of
// lifelong.cpp.
#pragma once

#include <CLI/CLI.hpp>

#include "apps/commands.hpp"

namespace lifelong::apps {

/// Adds the subcommand; `default_book` is the shipped book/chapter6.yaml.
CLI::App* AddReproduceCommand(CLI::App& app, ReproduceArgs* args, const std::string& default_book);

/// The error of options given without --slurm that need it, or "" (exit 2 then).
std::string ReproduceArgsProblem(const ReproduceArgs& args);

}  // namespace lifelong::apps
