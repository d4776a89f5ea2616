#include "eval/experiment/mapper_config_file.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "sensor/input_error.hpp"
#include "sim/yaml_fields.hpp"
#include "slam/mapping/mapper_config_fields.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::eval {
namespace {

using namespace slam::config_fields;  // NOLINT: the fields are this file's vocabulary

/// Keys that look like settings but are deliberately not in the file.
const std::map<std::string, std::string>& Hints() {
  static const std::map<std::string, std::string> hints = {
      {"pruning.mode", "the pruning mode is chosen with --modes, not in the config"},
      {"pruning.policy",
       "the removal policy is the mode's: --modes POLICY+SPARSIFIER (e.g. node-budget+glc)"},
      {"pruning.sparsifier",
       "the sparsifier is the mode's: --modes POLICY+SPARSIFIER (e.g. information-gain+glc)"},
      {"loops.matcher.linear_window_m", "set per attempt from loops.min_window_m..max_window_m"},
      {"loops.matcher.angular_window_rad",
       "set per attempt from loops.min_window_rad..max_window_rad"},
      {"optimizer.anchor", "the mapper always anchors the oldest node"}};
  return hints;
}

// ---- Reading: strict, every error an InputError with file, 1-based line and field. ----

using sim::LineOf;

class Reader {
 public:
  Reader(std::string file, YAML::Node node, std::string field)
      : file_(std::move(file)), node_(std::move(node)), field_(std::move(field)) {}

  template <class F>
  void Section(const char* key, F&& visit) {
    const YAML::Node n = Take(key);
    if (!n || n.IsNull()) return;  // an empty section changes nothing
    if (!n.IsMap()) Fail(n, Name(key), "expected a section of key: value pairs");
    Reader child(file_, n, Name(key));
    visit(child);
    child.RejectUnknown();
  }

  // The ranges are not checked here: slam::Validate checks every field of the result against
  // the same table, and the file's line is found from the field it names (LineOfField).
  void Number(const char* key, double& value, const Range&) {
    const YAML::Node n = Take(key);
    if (!n) return;
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, value)) {
      Fail(n, Name(key), "expected a number, got '" + Text(n) + "'");
    }
  }

  void Int(const char* key, int& value, int, int = 0) {
    const YAML::Node n = Take(key);
    if (!n) return;
    if (!n.IsScalar() || !YAML::convert<int>::decode(n, value)) {
      Fail(n, Name(key), "expected an integer, got '" + Text(n) + "'");
    }
  }

  void PowerOfTwo(const char* key, int& value) { Int(key, value, 1); }

  void Bool(const char* key, bool& value) {
    const YAML::Node n = Take(key);
    if (!n) return;
    if (!n.IsScalar() || !YAML::convert<bool>::decode(n, value)) {
      Fail(n, Name(key), "expected true or false, got '" + Text(n) + "'");
    }
  }

  template <class E, std::size_t N>
  void Enum(const char* key, E& value, const EnumName<E> (&names)[N]) {
    const YAML::Node n = Take(key);
    if (!n) return;
    std::string choices;
    for (const auto& [name, e] : names) {
      if (n.IsScalar() && n.Scalar() == name) {
        value = e;
        return;
      }
      choices += choices.empty() ? name : std::string(", ") + name;
    }
    Fail(n, Name(key), "expected one of " + choices + ", got '" + Text(n) + "'");
  }

  void Ordered(const char*, double, const char*, double) {}  // slam::Validate's

  /// Every key must be a known one, given once (yaml-cpp would silently keep the first).
  void RejectUnknown() const {
    sim::RejectDuplicateKeys(file_, node_, field_);
    for (auto it = node_.begin(); it != node_.end(); ++it) {
      const std::string key = it->first.Scalar();
      if (used_.count(key) != 0) continue;
      const auto hint = Hints().find(Name(key));
      Fail(it->first, Name(key),
           hint == Hints().end() ? "unknown key" : "unknown key: " + hint->second);
    }
  }

 private:
  const YAML::Node& Node() const { return node_; }  // const access never inserts keys
  YAML::Node Take(const char* key) {
    used_.insert(key);
    return Node()[key];
  }
  std::string Name(const std::string& key) const {
    return field_.empty() ? key : field_ + "." + key;
  }
  static std::string Text(const YAML::Node& n) {
    return n.IsScalar() ? n.Scalar() : "a non-scalar";
  }
  [[noreturn]] void Fail(const YAML::Node& at, const std::string& field,
                         const std::string& message) const {
    throw InputError(file_, at ? LineOf(at) : LineOf(node_), field, message);
  }

  std::string file_;
  YAML::Node node_;
  std::string field_;
  std::set<std::string> used_;
};

// The deepest node of the dotted `field` the file has, and whether that is the field itself.
std::pair<YAML::Node, bool> Walk(const YAML::Node& root, const std::string& field) {
  YAML::Node at = root;
  std::size_t start = 0;
  for (;;) {
    const std::size_t dot = field.find('.', start);
    const std::string key = field.substr(start, dot == std::string::npos ? dot : dot - start);
    const YAML::Node next = at.IsMap() ? static_cast<const YAML::Node&>(at)[key] : YAML::Node();
    if (!next) return {at, false};
    at.reset(next);  // rebinds; operator= would overwrite the node `at` refers to
    if (dot == std::string::npos) return {at, true};
    start = dot + 1;
  }
}

bool FileGives(const YAML::Node& root, const std::string& field) {
  return Walk(root, field).second;
}

// The line to blame for a problem Validate found: the first field it names, or the
// deepest section of it the file has (a bound across settings may come from defaults).
int LineOfField(const YAML::Node& root, const std::string& fields) {
  return LineOf(Walk(root, fields.substr(0, fields.find(','))).first);
}

ConfigFile Apply(const YAML::Node& root, const std::string& name, const slam::MapperConfig& base) {
  ConfigFile settings{base, {}};
  slam::MapperConfig& config = settings.mapper;
  if (!root || root.IsNull()) return settings;
  if (!root.IsMap()) throw InputError(name, LineOf(root), "", "expected a map of sections");
  Reader reader(name, root, "");
  VisitConfig(reader, config);
  reader.Section("false_closures",
                 [&](auto& s) { VisitFalseClosures(s, settings.false_closures); });
  reader.RejectUnknown();
  // The reader has mapped keys to fields; each config's Validate checks their values.
  std::optional<slam::ConfigProblem> problem = slam::Validate(config);
  if (!problem) problem = Validate(settings.false_closures);
  if (problem) {
    // A bound between two settings blames the one the file gives.
    const std::string& field = !problem->counterpart.empty() && !FileGives(root, problem->fields) &&
                                       FileGives(root, problem->counterpart)
                                   ? problem->counterpart
                                   : problem->fields;
    throw InputError(name, LineOfField(root, field), field, problem->message);
  }
  return settings;
}

YAML::Node LoadYamlFile(const std::string& path) {
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "", "cannot open the config file");
  } catch (const YAML::ParserException& e) {
    throw InputError(path, e.mark.line + 1, "", "malformed YAML: " + e.msg);
  }
}

YAML::Node ParseYaml(const std::string& yaml, const std::string& name) {
  try {
    return YAML::Load(yaml);
  } catch (const YAML::ParserException& e) {
    throw InputError(name, e.mark.line + 1, "", "malformed YAML: " + e.msg);
  }
}

/// Dotted settings as nested sections: {"a.b.c", v} -> a: {b: {c: v}}.
YAML::Node SettingsNode(const std::vector<std::pair<std::string, std::string>>& settings) {
  YAML::Node root(YAML::NodeType::Map);
  for (const auto& [key, value] : settings) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t dot; (dot = key.find('.', start)) != std::string::npos; start = dot + 1) {
      parts.push_back(key.substr(start, dot - start));
    }
    parts.push_back(key.substr(start));
    YAML::Node node = root;
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      if (!node[parts[i]] || !node[parts[i]].IsMap()) {
        node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      }
      node.reset(node[parts[i]]);
    }
    node[parts.back()] = value;
  }
  return root;
}

}  // namespace

slam::MapperConfig ApplyMapperSettings(
    const std::vector<std::pair<std::string, std::string>>& settings, const std::string& name,
    const slam::MapperConfig& base) {
  return Apply(SettingsNode(settings), name, base).mapper;
}

std::string MapperSettingsYaml(const std::vector<std::pair<std::string, std::string>>& settings) {
  const YAML::Node root = SettingsNode(settings);
  if (root.size() == 0) return "{}\n";
  YAML::Emitter out;
  out << root;
  return std::string(out.c_str()) + "\n";
}

slam::MapperConfig LoadMapperConfigFromString(const std::string& yaml, const std::string& name,
                                              const slam::MapperConfig& base) {
  return Apply(ParseYaml(yaml, name), name, base).mapper;
}

ConfigFile LoadConfigFile(const std::string& path) {
  return Apply(LoadYamlFile(path), path, slam::MapperConfig{});
}

slam::MapperConfig LoadMapperConfig(const std::string& path, const slam::MapperConfig& base) {
  return Apply(LoadYamlFile(path), path, base).mapper;
}

FalseClosureConfig LoadFalseClosureConfig(const std::string& path) {
  return LoadConfigFile(path).false_closures;
}

FalseClosureConfig FalseClosureConfigFromString(const std::string& yaml, const std::string& name) {
  return Apply(ParseYaml(yaml, name), name, slam::MapperConfig{}).false_closures;
}

}  // namespace lifelong::eval
