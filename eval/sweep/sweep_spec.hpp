// The SPEC file of `lifelong sweep` (docs/sweeps.md): which scenarios and logs to map,
// with which seeds, modes and mapper settings. Read strictly: an unknown key, an empty
// list, a missing scenario, world or log, an unknown mode or an unknown mapper setting is
// a lifelong::InputError naming the SPEC file, the line and the field, before anything runs.
//
//   scenarios: [../scenarios/corridor_3.yaml]      # paths relative to the SPEC file
//   logs: [{log: a.clf.gz, relations: a.relations, relations_offset_s: 0, seeded: true}]
//   seeds: [1, 2, 3]                   # override each scenario's seed; absent: its own;
//                                      # a seeded log is replayed as one draw per seed
//   modes: [standard, pruned]
//   settings: {pruning.gain_threshold_bits: [0, 5]}   # dotted mapper-config keys
//   baseline: standard                 # default: the first mode
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace lifelong::eval {

/// One scenario or log of the SPEC, its paths resolved against the SPEC's folder.
struct SweepSource {
  bool is_log = false;
  std::string given;                         ///< as written in the SPEC
  std::string path;                          ///< absolute
  std::string world_path;                    ///< scenarios: the world file, absolute
  std::string relations;                     ///< logs: relations file, absolute; empty: none
  std::optional<double> relations_offset_s;  ///< logs: given offset; absent: detected
  bool seeded = false;  ///< logs: replayed once per seed as draws (replay --seed); else once
  int line = 0;         ///< in the SPEC
};

/// One dotted mapper-config key and the values it takes (YAML scalars, as written).
struct SweepSetting {
  std::string key;
  std::vector<std::string> values;
  int line = 0;
};

struct SweepSpec {
  std::string file;  ///< the SPEC path as given
  std::vector<SweepSource> sources;
  std::vector<std::int64_t> seeds;  ///< empty: each scenario keeps its own seed
  std::vector<std::string> modes;   ///< the baseline first, then the others as given
  std::string baseline;
  std::vector<SweepSetting> settings;
  /// With MissingLogs::kRecord: the logs named but not found (absolute), left out of sources.
  std::vector<std::string> missing_logs;
};

/// What a log that does not exist is: an error (the default), or a note in missing_logs
/// (a book's experiment on public logs the project does not ship, eval/book/book.hpp).
enum class MissingLogs { kRefuse, kRecord };

/// Reads and checks `path` (see above). Throws lifelong::InputError.
SweepSpec LoadSweepSpec(const std::string& path, MissingLogs missing = MissingLogs::kRefuse);

}  // namespace lifelong::eval
