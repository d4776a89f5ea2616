// Internal: strict YAML reading for the world and scenario loaders. Every error becomes a
// lifelong::InputError with the file, the 1-based line and the dotted field name.
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

#include "sim/geometry.hpp"

namespace lifelong::sim {

/// 1-based line of a node, 0 when unknown.
int LineOf(const YAML::Node& node);
[[noreturn]] void Fail(const std::string& file, const YAML::Node& node, const std::string& field,
                       const std::string& message);

/// Parses a YAML document; syntax errors and unreadable files become InputError.
YAML::Node ParseYamlFile(const std::string& path);
YAML::Node ParseYamlString(const std::string& text, const std::string& name);

double AsDouble(const std::string& file, const YAML::Node& n, const std::string& field);
int AsInt(const std::string& file, const YAML::Node& n, const std::string& field);
std::string AsString(const std::string& file, const YAML::Node& n, const std::string& field);
Point AsPoint(const std::string& file, const YAML::Node& n, const std::string& field);
std::vector<Point> AsPoints(const std::string& file, const YAML::Node& n, const std::string& field);

/// Rejects a map that gives a key twice (yaml-cpp would silently keep the first value):
/// InputError at the repeated key's line naming the dotted field ("" for the document root).
void RejectDuplicateKeys(const std::string& file, const YAML::Node& map, const std::string& field);

/// A YAML map read key by key. Construction rejects duplicate keys (RejectDuplicateKeys);
/// Finish() rejects keys that were never asked for.
class Fields {
 public:
  Fields(std::string file, const YAML::Node& node, std::string field);

  bool Has(const std::string& key) const;
  YAML::Node Required(const std::string& key);
  YAML::Node Optional(const std::string& key);
  double Double(const std::string& key);
  double Double(const std::string& key, double fallback);
  int Int(const std::string& key, int fallback);
  bool Bool(const std::string& key, bool fallback);
  std::string String(const std::string& key);
  Point GetPoint(const std::string& key);
  /// Dotted name of a child field, e.g. "laser.rate_hz".
  std::string Name(const std::string& key) const;
  /// Throws InputError for the value of `key`: its own line (the map's line when the key is
  /// absent, i.e. a default is wrong) and its dotted name. Checks of a read value use this,
  /// so an error never names a neighbouring key or the section.
  [[noreturn]] void FailAt(const std::string& key, const std::string& message) const;
  const std::string& file() const { return file_; }
  const YAML::Node& node() const { return node_; }
  void Finish() const;

 private:
  std::string file_;
  YAML::Node node_;
  std::string field_;
  std::set<std::string> used_;
};

}  // namespace lifelong::sim
