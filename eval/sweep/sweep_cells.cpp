#include "eval/sweep/sweep_cells.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "eval/experiment/mapper_config_file.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;
using Settings = std::vector<std::pair<std::string, std::string>>;

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string SafeName(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ||
                    c == '.' || c == '=' || c == '+';
    out += ok ? c : '_';
  }
  return out;
}

// "intel-raw-first1088s.clf.gz" -> "intel-raw-first1088s"; "corridor_3.yaml" -> "corridor_3".
std::string Stem(const std::string& path) {
  fs::path p = fs::path(path).filename();
  if (p.extension() == ".gz") p = p.stem();
  return p.stem().string();
}

// Every combination of the settings' values, the last key varying fastest.
std::vector<Settings> Combinations(const std::vector<SweepSetting>& settings) {
  std::vector<Settings> out{{}};
  for (const SweepSetting& s : settings) {
    std::vector<Settings> next;
    for (const Settings& partial : out) {
      for (const std::string& v : s.values) {
        next.push_back(partial);
        next.back().emplace_back(s.key, v);
      }
    }
    out = std::move(next);
  }
  return out;
}

// The last part of each key names it, unless two keys share that part.
std::string CellName(const SweepSource& source, const SweepPlanCell& cell, bool full_keys) {
  std::string name = Stem(source.path);
  if (cell.seed) name += "-seed" + std::to_string(*cell.seed);
  for (const auto& [key, value] : cell.settings) {
    name += "-" + (full_keys ? key : key.substr(key.rfind('.') + 1)) + "=" + value;
  }
  return SafeName(name);
}

// Scenario text, seed, world text, config text, modes, program: what makes a result.
std::string CellHash(const SweepSpec& spec, const SweepSource& source, const SweepPlanCell& cell,
                     const std::string& config_yaml, const std::string& program) {
  std::string key = "lifelong-sweep-cell-v1";
  const auto add = [&key](const std::string& part) {
    key += '\0' + std::to_string(part.size()) + ':' + part;
  };
  add(source.is_log ? "replay" : "run");
  add(ReadBytes(source.path));
  add(source.is_log ? "" : ReadBytes(source.world_path));
  add(source.relations.empty() ? "" : ReadBytes(source.relations));
  add(source.relations_offset_s ? std::to_string(*source.relations_offset_s) : "detected");
  add(cell.seed ? std::to_string(*cell.seed) : "own");
  add(config_yaml);
  for (const std::string& m : spec.modes) add(m);
  add(program);
  return HashHex(key);
}

const SweepSource& SourceOf(const SweepSpec& spec, const SweepPlanCell& cell) {
  for (const SweepSource& s : spec.sources) {
    if (s.given == cell.source && s.is_log == cell.is_log) return s;
  }
  throw std::logic_error("sweep cell " + cell.name + ": source not in the spec");
}

}  // namespace

std::string HashHex(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

SweepPlan ExpandSweep(const SweepSpec& spec, const std::string& program) {
  SweepPlan plan;
  plan.spec = spec.file;
  plan.modes = spec.modes;
  plan.baseline = spec.baseline;
  for (const SweepSetting& s : spec.settings) plan.setting_keys.push_back(s.key);
  const std::vector<Settings> combinations = Combinations(spec.settings);
  std::map<std::string, int> lines;  // name -> SPEC line of its source
  std::set<std::string> last_parts;
  for (const std::string& key : plan.setting_keys)
    last_parts.insert(key.substr(key.rfind('.') + 1));
  const bool full_keys = last_parts.size() < plan.setting_keys.size();
  for (const SweepSource& source : spec.sources) {
    std::vector<std::optional<std::int64_t>> seeds;
    // A log is replayed as recorded, or, seeded, as one draw per seed (replay --seed).
    const bool per_seed = !source.is_log || source.seeded;
    if (!per_seed || spec.seeds.empty()) seeds.push_back(std::nullopt);
    if (per_seed) seeds.insert(seeds.end(), spec.seeds.begin(), spec.seeds.end());
    for (const auto& seed : seeds) {
      for (const Settings& settings : combinations) {
        SweepPlanCell cell{"", source.given, source.is_log, seed, settings, "", {}, ""};
        cell.name = CellName(source, cell, full_keys);
        const std::string config = MapperSettingsYaml(settings);
        try {  // a combination can break a rule one value alone keeps (min <= max)
          ApplyMapperSettings(settings, "settings");
        } catch (const InputError& e) {
          throw InputError(spec.file, spec.settings.empty() ? 0 : spec.settings.front().line,
                           "settings", "the combination of cell " + cell.name + ": " + e.what());
        }
        if (!lines.emplace(cell.name, source.line).second) {
          throw InputError(spec.file, source.line, cell.source,
                           "gives the same cell name as line " + std::to_string(lines[cell.name]) +
                               " (" + cell.name + "): rename one of the files");
        }
        cell.hash = CellHash(spec, source, cell, config, program);
        plan.cells.push_back(std::move(cell));
      }
    }
  }
  return plan;
}

CellInputs MakeCellInputs(const SweepSpec& spec, const SweepPlanCell& cell) {
  CellInputs in;
  in.config_yaml = MapperSettingsYaml(cell.settings);
  const SweepSource& source = SourceOf(spec, cell);
  if (source.is_log) return in;
  YAML::Node scenario = YAML::LoadFile(source.path);
  scenario["world"] = source.world_path;
  if (cell.seed) scenario["seed"] = *cell.seed;
  YAML::Emitter out;
  out << scenario;
  in.scenario_yaml =
      "# generated by lifelong sweep from " + source.path + "\n" + out.c_str() + "\n";
  return in;
}

std::vector<std::string> CellCommand(const std::string& program, const SweepSpec& spec,
                                     const SweepPlanCell& cell, const std::string& input,
                                     const std::string& config, const std::string& out_dir) {
  const SweepSource& source = SourceOf(spec, cell);
  std::string modes;
  for (const std::string& m : spec.modes) modes += (modes.empty() ? "" : ",") + m;
  std::vector<std::string> argv{program,
                                source.is_log ? "replay" : "run",
                                source.is_log ? source.path : input,
                                "-o",
                                out_dir,
                                "--modes",
                                modes,
                                "--config",
                                config};
  if (source.is_log && cell.seed) argv.insert(argv.end(), {"--seed", std::to_string(*cell.seed)});
  if (!source.relations.empty()) {
    argv.insert(argv.end(), {"--relations", source.relations});
    if (source.relations_offset_s) {
      std::ostringstream s;
      s.precision(17);
      s << *source.relations_offset_s;
      argv.insert(argv.end(), {"--relations-offset", s.str()});
    }
  }
  return argv;
}

}  // namespace lifelong::eval
