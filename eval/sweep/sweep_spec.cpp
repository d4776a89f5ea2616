#include "eval/sweep/sweep_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <utility>

#include "eval/experiment/mapper_config_file.hpp"
#include "sensor/input_error.hpp"
#include "sim/yaml_fields.hpp"
#include "slam/mapping/mapper_config.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

using sim::LineOf;

class SpecReader {
 public:
  SpecReader(std::string file, YAML::Node root, MissingLogs missing)
      : file_(std::move(file)), root_(std::move(root)), missing_(missing) {
    dir_ = fs::absolute(fs::path(file_)).parent_path();
  }

  [[noreturn]] void Fail(const YAML::Node& at, const std::string& field,
                         const std::string& message) const {
    throw InputError(file_, at ? LineOf(at) : 0, field, message);
  }

  /// A list that is present must be a non-empty sequence.
  YAML::Node List(const YAML::Node& n, const std::string& field) const {
    if (!n.IsSequence()) Fail(n, field, "expected a list");
    if (n.size() == 0) Fail(n, field, "the list is empty");
    return n;
  }

  std::string Scalar(const YAML::Node& n, const std::string& field) const {
    if (!n.IsScalar() || n.Scalar().empty()) Fail(n, field, "expected a value");
    return n.Scalar();
  }

  /// A file named relative to the SPEC's folder, made absolute.
  std::string Resolved(const YAML::Node& n, const std::string& field) const {
    return (dir_ / Scalar(n, field)).lexically_normal().string();
  }

  /// An existing file named relative to the SPEC's folder, made absolute.
  std::string ExistingFile(const YAML::Node& n, const std::string& field,
                           const std::string& what) const {
    const std::string p = Resolved(n, field);
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) Fail(n, field, "no such " + what + ": " + p);
    return p;
  }

  void RejectUnknown(const YAML::Node& map, const std::set<std::string>& known,
                     const std::string& prefix) const {
    sim::RejectDuplicateKeys(file_, map,
                             prefix.empty() ? prefix : prefix.substr(0, prefix.size() - 1));
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string key = it->first.Scalar();
      if (known.count(key) == 0) Fail(it->first, prefix + key, "unknown key");
    }
  }

  SweepSource Scenario(const YAML::Node& n, const std::string& field) const {
    SweepSource s;
    s.given = Scalar(n, field);
    s.path = ExistingFile(n, field, "scenario");
    s.line = LineOf(n);
    YAML::Node scenario;
    try {
      scenario = YAML::LoadFile(s.path);
    } catch (const YAML::Exception& e) {
      Fail(n, field, "the scenario " + s.path + " is not YAML: " + e.what());
    }
    const YAML::Node world = scenario.IsMap() ? scenario["world"] : YAML::Node();
    if (!world || !world.IsScalar()) Fail(n, field, "the scenario " + s.path + " names no world");
    const fs::path w = fs::path(s.path).parent_path() / world.Scalar();
    std::error_code ec;
    if (!fs::is_regular_file(w, ec)) {
      Fail(n, field, "the world of " + s.path + " does not exist: " + w.string());
    }
    s.world_path = w.lexically_normal().string();
    return s;
  }

  SweepSource Log(const YAML::Node& n, const std::string& field) const {
    SweepSource s;
    s.is_log = true;
    s.line = LineOf(n);
    const YAML::Node log = n.IsMap() ? n["log"] : n;
    if (n.IsMap()) {
      RejectUnknown(n, {"log", "relations", "relations_offset_s", "seeded"}, field + ".");
      if (!log) Fail(n, field + ".log", "missing");
      if (n["relations"]) {
        s.relations = ExistingFile(n["relations"], field + ".relations", "relations file");
      }
      if (const YAML::Node off = n["relations_offset_s"]) {
        double v = 0.0;
        if (!off.IsScalar() || !YAML::convert<double>::decode(off, v) || !std::isfinite(v)) {
          Fail(off, field + ".relations_offset_s", "expected a finite number of seconds");
        }
        s.relations_offset_s = v;
      }
      if (const YAML::Node seeded = n["seeded"]) {
        if (!seeded.IsScalar() || !YAML::convert<bool>::decode(seeded, s.seeded)) {
          Fail(seeded, field + ".seeded", "expected true or false");
        }
      }
    }
    const std::string at = field + (n.IsMap() ? ".log" : "");
    s.given = Scalar(log, at);
    // kRecord: Read() sets a missing log aside.
    s.path = missing_ == MissingLogs::kRecord ? Resolved(log, at) : ExistingFile(log, at, "log");
    return s;
  }

  void Read(SweepSpec* spec) const {
    if (!root_.IsMap()) Fail(root_, "", "expected a map (scenarios, logs, seeds, modes, ...)");
    RejectUnknown(root_, {"scenarios", "logs", "seeds", "modes", "settings", "baseline"}, "");
    if (const YAML::Node list = root_["scenarios"]) {
      for (std::size_t i = 0; i < List(list, "scenarios").size(); ++i) {
        spec->sources.push_back(Scenario(list[i], "scenarios[" + std::to_string(i) + "]"));
      }
    }
    if (const YAML::Node list = root_["logs"]) {
      for (std::size_t i = 0; i < List(list, "logs").size(); ++i) {
        const SweepSource log = Log(list[i], "logs[" + std::to_string(i) + "]");
        std::error_code ec;
        if (missing_ == MissingLogs::kRecord && !fs::is_regular_file(log.path, ec)) {
          spec->missing_logs.push_back(log.path);
        } else {
          spec->sources.push_back(log);
        }
      }
    }
    if (spec->sources.empty() && spec->missing_logs.empty()) {
      Fail(root_, "scenarios", "neither scenarios nor logs are given");
    }
    ReadSeeds(spec);
    ReadModes(spec);
    ReadSettings(spec);
  }

 private:
  void ReadSeeds(SweepSpec* spec) const {
    const YAML::Node list = root_["seeds"];
    if (!list) return;
    std::set<std::int64_t> seen;
    for (std::size_t i = 0; i < List(list, "seeds").size(); ++i) {
      std::int64_t seed = 0;
      const std::string field = "seeds[" + std::to_string(i) + "]";
      if (!list[i].IsScalar() || !YAML::convert<std::int64_t>::decode(list[i], seed) || seed < 0) {
        Fail(list[i], field, "expected an integer >= 0");
      }
      if (!seen.insert(seed).second) Fail(list[i], field, "seed given twice");
      spec->seeds.push_back(seed);
    }
  }

  void ReadModes(SweepSpec* spec) const {
    const YAML::Node list = root_["modes"];
    if (!list) Fail(root_, "modes", "missing (e.g. modes: [standard, pruned])");
    for (std::size_t i = 0; i < List(list, "modes").size(); ++i) {
      const std::string field = "modes[" + std::to_string(i) + "]";
      const std::string name = Scalar(list[i], field);
      if (!slam::ParseMode(name)) {
        Fail(list[i], field, "unknown mode '" + name + "' (known: " + slam::ModeList() + ")");
      }
      if (std::count(spec->modes.begin(), spec->modes.end(), name)) {
        Fail(list[i], field, "mode named twice");
      }
      spec->modes.push_back(name);
    }
    spec->baseline = spec->modes.front();
    if (const YAML::Node b = root_["baseline"]) {
      spec->baseline = Scalar(b, "baseline");
      const auto it = std::find(spec->modes.begin(), spec->modes.end(), spec->baseline);
      if (it == spec->modes.end()) Fail(b, "baseline", "is not one of the modes");
      std::rotate(spec->modes.begin(), it, it + 1);  // the baseline first, as --modes wants
    }
  }

  void ReadSettings(SweepSpec* spec) const {
    const YAML::Node map = root_["settings"];
    if (!map) return;
    if (!map.IsMap() || map.size() == 0) {
      Fail(map, "settings", "expected dotted mapper-config keys, each with a list of values");
    }
    RejectDuplicates(map);
    for (auto it = map.begin(); it != map.end(); ++it) {
      SweepSetting s;
      s.key = it->first.Scalar();
      s.line = LineOf(it->first);
      const std::string field = "settings." + s.key;
      for (std::size_t i = 0; i < List(it->second, field).size(); ++i) {
        s.values.push_back(Scalar(it->second[i], field + "[" + std::to_string(i) + "]"));
        CheckSetting(s.key, s.values.back(), it->second[i]);
      }
      spec->settings.push_back(std::move(s));
    }
  }

  void RejectDuplicates(const YAML::Node& map) const {
    sim::RejectDuplicateKeys(file_, map, "settings");
  }

  /// The real config reader decides: this key and value alone must apply.
  void CheckSetting(const std::string& key, const std::string& value, const YAML::Node& at) const {
    try {
      ApplyMapperSettings({{key, value}}, "setting");
    } catch (const InputError& e) {
      Fail(at, "settings." + key,
           std::string("not a valid mapper setting (configs/default.yaml): ") + e.what());
    }
  }

  std::string file_;
  YAML::Node root_;
  MissingLogs missing_;
  fs::path dir_;
};

}  // namespace

SweepSpec LoadSweepSpec(const std::string& path, MissingLogs missing) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "", "cannot open the sweep spec");
  } catch (const YAML::ParserException& e) {
    throw InputError(path, e.mark.line + 1, "", "malformed YAML: " + e.msg);
  }
  SweepSpec spec;
  spec.file = path;
  SpecReader(path, root, missing).Read(&spec);
  return spec;
}

}  // namespace lifelong::eval
