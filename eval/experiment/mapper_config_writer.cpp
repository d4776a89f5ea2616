// Writing a MapperConfig as YAML (every key, in the order of mapper_config_fields.hpp).
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "eval/experiment/mapper_config_file.hpp"
#include "slam/mapping/mapper_config_fields.hpp"

namespace lifelong::eval {
namespace {

using namespace slam::config_fields;  // NOLINT: the fields are this file's vocabulary

class Writer {
 public:
  explicit Writer(YAML::Emitter* out) : out_(*out) {}

  template <class F>
  void Section(const char* key, F&& visit) {
    out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
    visit(*this);
    out_ << YAML::EndMap;
  }
  void Number(const char* key, double value, const Range&) { Put(key, ShortestDouble(value)); }
  void Int(const char* key, int value, int, int = 0) { Put(key, std::to_string(value)); }
  void PowerOfTwo(const char* key, int value) { Put(key, std::to_string(value)); }
  void Bool(const char* key, bool value) { Put(key, value ? "true" : "false"); }
  template <class E, std::size_t N>
  void Enum(const char* key, E value, const EnumName<E> (&names)[N]) {
    for (const auto& [name, e] : names) {
      if (e == value) Put(key, name);
    }
  }
  void Ordered(const char*, double, const char*, double) {}

 private:
  void Put(const char* key, const std::string& text) {
    out_ << YAML::Key << key << YAML::Value << text;
  }
  YAML::Emitter& out_;
};

}  // namespace

std::string MapperConfigToYaml(const slam::MapperConfig& config,
                               const FalseClosureConfig& false_closures) {
  slam::MapperConfig copy = config;
  FalseClosureConfig test = false_closures;
  YAML::Emitter out;
  out << YAML::BeginMap;
  Writer writer(&out);
  VisitConfig(writer, copy);
  writer.Section("false_closures", [&](auto& s) { VisitFalseClosures(s, test); });
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace lifelong::eval
