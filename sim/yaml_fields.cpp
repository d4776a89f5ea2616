#include "sim/yaml_fields.hpp"

#include "sensor/input_error.hpp"

namespace lifelong::sim {

int LineOf(const YAML::Node& node) {
  const int line = node.Mark().line;
  return line >= 0 ? line + 1 : 0;
}

void Fail(const std::string& file, const YAML::Node& node, const std::string& field,
          const std::string& message) {
  throw InputError(file, LineOf(node), field, message);
}

YAML::Node ParseYamlFile(const std::string& path) {
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "", "cannot open file");
  } catch (const YAML::ParserException& e) {
    throw InputError(path, e.mark.line + 1, "", "YAML syntax error: " + e.msg);
  }
}

YAML::Node ParseYamlString(const std::string& text, const std::string& name) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(name, e.mark.line + 1, "", "YAML syntax error: " + e.msg);
  }
}

double AsDouble(const std::string& file, const YAML::Node& n, const std::string& field) {
  if (!n.IsScalar()) Fail(file, n, field, "expected a number");
  try {
    return n.as<double>();
  } catch (const YAML::Exception&) {
    Fail(file, n, field, "expected a number, got '" + n.Scalar() + "'");
  }
}

int AsInt(const std::string& file, const YAML::Node& n, const std::string& field) {
  if (!n.IsScalar()) Fail(file, n, field, "expected an integer");
  try {
    return n.as<int>();
  } catch (const YAML::Exception&) {
    Fail(file, n, field, "expected an integer, got '" + n.Scalar() + "'");
  }
}

std::string AsString(const std::string& file, const YAML::Node& n, const std::string& field) {
  if (!n.IsScalar()) Fail(file, n, field, "expected a string");
  return n.Scalar();
}

Point AsPoint(const std::string& file, const YAML::Node& n, const std::string& field) {
  if (!n.IsSequence() || n.size() != 2) Fail(file, n, field, "expected a point [x, y] in metres");
  return {AsDouble(file, n[0], field), AsDouble(file, n[1], field)};
}

std::vector<Point> AsPoints(const std::string& file, const YAML::Node& n,
                            const std::string& field) {
  if (!n.IsSequence()) Fail(file, n, field, "expected a list of points [[x, y], ...]");
  std::vector<Point> out;
  for (const YAML::Node& p : n) out.push_back(AsPoint(file, p, field));
  return out;
}

void RejectDuplicateKeys(const std::string& file, const YAML::Node& map, const std::string& field) {
  std::set<std::string> seen;
  for (auto it = map.begin(); it != map.end(); ++it) {
    if (!it->first.IsScalar()) continue;  // never a known key: Finish() rejects it
    const std::string key = it->first.Scalar();
    if (!seen.insert(key).second) {
      Fail(file, it->first, field.empty() ? key : field + "." + key, "duplicate key");
    }
  }
}

Fields::Fields(std::string file, const YAML::Node& node, std::string field)
    : file_(std::move(file)), node_(node), field_(std::move(field)) {
  if (!node_.IsMap()) {
    Fail(file_, node_, field_, "expected a map of key: value");
  }
  RejectDuplicateKeys(file_, node_, field_);
}

bool Fields::Has(const std::string& key) const { return static_cast<bool>(node_[key]); }

YAML::Node Fields::Required(const std::string& key) {
  used_.insert(key);
  const YAML::Node n = node_[key];
  if (!n) Fail(file_, node_, Name(key), "missing required field");
  return n;
}

YAML::Node Fields::Optional(const std::string& key) {
  used_.insert(key);
  return node_[key];
}

double Fields::Double(const std::string& key) { return AsDouble(file_, Required(key), Name(key)); }

double Fields::Double(const std::string& key, double fallback) {
  const YAML::Node n = Optional(key);
  return n ? AsDouble(file_, n, Name(key)) : fallback;
}

int Fields::Int(const std::string& key, int fallback) {
  const YAML::Node n = Optional(key);
  return n ? AsInt(file_, n, Name(key)) : fallback;
}

bool Fields::Bool(const std::string& key, bool fallback) {
  const YAML::Node n = Optional(key);
  if (!n) return fallback;
  bool value = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, value)) {
    Fail(file_, n, Name(key), "expected true or false");
  }
  return value;
}

std::string Fields::String(const std::string& key) {
  return AsString(file_, Required(key), Name(key));
}

Point Fields::GetPoint(const std::string& key) { return AsPoint(file_, Required(key), Name(key)); }

std::string Fields::Name(const std::string& key) const {
  return field_.empty() ? key : field_ + "." + key;
}

void Fields::FailAt(const std::string& key, const std::string& message) const {
  const YAML::Node n = node_[key];  // const access: never inserts the key
  Fail(file_, n ? n : node_, Name(key), message);
}

void Fields::Finish() const {
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (used_.count(key) == 0) Fail(file_, it->first, Name(key), "unknown key");
  }
}

}  // namespace lifelong::sim
