// The expanded sweep as `DIR/sweep.json`: what `lifelong sweep` runs and what
// `lifelong sweep collect DIR` reads back, so that collecting needs nothing but DIR.
//   {"spec": "...", "modes": ["standard", "pruned"], "baseline": "standard",
//    "setting_keys": ["pruning.gain_threshold_bits"],
//    "cells": [{"name": "corridor_3-seed1-gain_threshold_bits=0", "source": "...",
//               "is_log": false, "seed": 1, "settings": {"pruning.gain_threshold_bits": "0"},
//               "hash": "5f0c..."}]}
// A cell's run writes its outputs to DIR/cells/<name>/ and, when it succeeded,
// DIR/cells/<name>/sweep_cell.json = {"hash": ...}: the result of exactly those inputs.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lifelong::eval {

struct SweepPlanCell {
  std::string name;
  std::string source;  ///< the scenario or log as written in the SPEC
  bool is_log = false;
  std::optional<std::int64_t> seed;  ///< absent: the scenario's own seed (or a log)
  std::vector<std::pair<std::string, std::string>> settings;  ///< key, value; SPEC order
  std::string hash;  ///< of the cell's inputs and the program (sweep_cells.hpp)
  /// The cell's command line (absolute paths) and its log: what the local pool and
  /// `lifelong sweep run-cell DIR INDEX` (a Slurm task) run. Empty in older plans.
  std::vector<std::string> argv;
  std::string log;
};

struct SweepPlan {
  std::string spec;
  std::vector<std::string> modes;  ///< the baseline first
  std::string baseline;
  std::vector<std::string> setting_keys;
  std::vector<SweepPlanCell> cells;
  std::string program_id;  ///< version and commit of the program that wrote the plan
};

/// Name of the file in a finished cell's directory that records its inputs' hash.
inline constexpr const char* kCellStampFile = "sweep_cell.json";

std::string SweepPlanToJson(const SweepPlan& plan);
/// Throws lifelong::InputError naming `file` when the text is not a sweep plan.
SweepPlan SweepPlanFromJson(const std::string& text, const std::string& file);

/// Reads DIR/sweep.json. Throws lifelong::InputError.
SweepPlan ReadSweepPlan(const std::string& dir);

/// The hash recorded in DIR/cells/<name>/sweep_cell.json, if that file exists and holds
/// one and the cell's summary.json exists too; else empty.
std::string FinishedCellHash(const std::string& cell_dir);

}  // namespace lifelong::eval
