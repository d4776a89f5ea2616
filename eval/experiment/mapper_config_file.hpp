// The mapper's settings as a YAML file (`lifelong run|replay --config FILE`), read strictly and
// written back, so a run can record exactly what it used (DIR/config.yaml).
//
// Layout: one section per nested struct of slam::MapperConfig, keys equal to the C++ field
// names (configs/default.yaml documents every key with its default, unit and meaning):
//   keyframes, incremental (+ matcher), loops (+ matcher), pruning, grid, optimizer, map_update
// Enums by name: optimizer.method lm|gn, optimizer.robust_kernel none|huber|cauchy|dcs,
// optimizer.linear_solver auto|simplicial|supernodal.
// Not in the file: pruning.mode (chosen with --modes), loops.matcher's two windows (set per
// attempt from loops.{min,max}_window_*), optimizer.anchor (always the oldest node).
//
// Errors are lifelong::InputError(file, 1-based line, dotted field, message): malformed YAML,
// an unknown key, a wrong type, a value out of range (e.g. a negative distance, a resolution
// <= 0, a coarse_factor that is not a power of 2, a score outside [0, 1]).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "eval/experiment/false_closures.hpp"
#include "slam/mapping/mapper_config.hpp"

namespace lifelong::eval {

/// Reads `path` and applies it on top of `base`: settings the file does not give keep the
/// value of `base` (pruning.mode always does). An empty file gives `base`.
slam::MapperConfig LoadMapperConfig(const std::string& path,
                                    const slam::MapperConfig& base = slam::MapperConfig{});

/// Same, from a YAML text; `name` stands for the file name in error messages.
slam::MapperConfig LoadMapperConfigFromString(
    const std::string& yaml, const std::string& name,
    const slam::MapperConfig& base = slam::MapperConfig{});

/// Dotted settings ("loops.verify.min_group", "4"), as a sweep gives them, applied on top of
/// `base` by the same reader and checks as a file, with no text in between; `name` stands for
/// the file name in error messages.
slam::MapperConfig ApplyMapperSettings(
    const std::vector<std::pair<std::string, std::string>>& settings, const std::string& name,
    const slam::MapperConfig& base = slam::MapperConfig{});

/// A config file: the mapper's settings over the defaults, and eval's `false_closures`
/// section, read and checked in one pass (what `run` and `replay` take from --config).
struct ConfigFile {
  slam::MapperConfig mapper;
  FalseClosureConfig false_closures;
};
ConfigFile LoadConfigFile(const std::string& path);

/// The file's `false_closures` section (eval's false-closure test, false_closures.hpp), read
/// with the same checks as the rest of the file; its defaults (off) when the file has none.
FalseClosureConfig LoadFalseClosureConfig(const std::string& path);
/// Same, from a YAML text; `name` stands for the file name in error messages.
FalseClosureConfig FalseClosureConfigFromString(const std::string& yaml, const std::string& name);

/// The same settings as a YAML document that LoadMapperConfigFromString reads to the config
/// ApplyMapperSettings gives ("{}" for none): a sweep cell's config file.
std::string MapperSettingsYaml(const std::vector<std::pair<std::string, std::string>>& settings);

/// Every setting of `config` (except those listed above), then the `false_closures` section,
/// as a YAML document that LoadMapperConfigFromString and LoadFalseClosureConfig read back to
/// equal configs (doubles in shortest exact form): a run's config.yaml.
std::string MapperConfigToYaml(const slam::MapperConfig& config,
                               const FalseClosureConfig& false_closures = {});

}  // namespace lifelong::eval
