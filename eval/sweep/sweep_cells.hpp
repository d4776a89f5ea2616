// The cells of a sweep: every scenario × seed × setting combination, and every log ×
// setting combination (logs have no seed). Each cell is one `lifelong run` (or `replay`)
// with every mode, given a generated scenario copy (the seed overridden, `world:` made
// absolute) and a generated `--config` holding the cell's settings as nested YAML.
#pragma once

#include <string>
#include <vector>

#include "eval/sweep/sweep_plan.hpp"
#include "eval/sweep/sweep_spec.hpp"

namespace lifelong::eval {

/// What a cell's run is given, generated from the SPEC.
struct CellInputs {
  std::string scenario_yaml;  ///< scenarios: the copy to run; logs: empty
  std::string config_yaml;    ///< the --config file
};

/// Expands the SPEC into cells (names unique and file-safe) with the hash of their inputs
/// (`program` stands for the program's version and commit). Every cell's config is loaded
/// through the real config reader first. Throws lifelong::InputError naming the SPEC file.
SweepPlan ExpandSweep(const SweepSpec& spec, const std::string& program);

/// The inputs of plan cell `i` (cells and sources share their order, see ExpandSweep).
CellInputs MakeCellInputs(const SweepSpec& spec, const SweepPlanCell& cell);

/// The command line of a cell: `program run SCENARIO ...` or `program replay LOG ...`.
/// `input` is the generated scenario copy (scenarios) and is ignored for logs.
std::vector<std::string> CellCommand(const std::string& program, const SweepSpec& spec,
                                     const SweepPlanCell& cell, const std::string& input,
                                     const std::string& config, const std::string& out_dir);

/// FNV-1a 64 of `bytes`, as 16 hex digits.
std::string HashHex(const std::string& bytes);

}  // namespace lifelong::eval
