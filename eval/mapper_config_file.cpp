#include "eval/mapper_config_file.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "sensor/input_error.hpp"
#include "slam/removal_policy.hpp"
#include "slam/sparsifier.hpp"

namespace lifelong::eval {
namespace {

using slam::LinearSolver;
using slam::OptimizerMethod;
using slam::RobustKernel;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Allowed values of a number: [min, max], or (min, max] when min_open.
struct Range {
  double min;
  double max;
  bool min_open;
  const char* text;
};
constexpr Range kAnyNumber{-kInf, kInf, false, "a finite number"};
constexpr Range kNonNegative{0.0, kInf, false, ">= 0"};
constexpr Range kPositive{0.0, kInf, true, "> 0"};
constexpr Range kUnit{0.0, 1.0, false, "in [0, 1]"};

template <class E>
struct EnumName {
  const char* name;
  E value;
};
constexpr EnumName<OptimizerMethod> kMethods[] = {{"lm", OptimizerMethod::kLevenbergMarquardt},
                                                  {"gn", OptimizerMethod::kGaussNewton}};
constexpr EnumName<RobustKernel> kKernels[] = {{"none", RobustKernel::kNone},
                                               {"huber", RobustKernel::kHuber},
                                               {"cauchy", RobustKernel::kCauchy},
                                               {"dcs", RobustKernel::kDcs}};
constexpr EnumName<LinearSolver> kSolvers[] = {{"auto", LinearSolver::kAuto},
                                               {"simplicial", LinearSolver::kSimplicial},
                                               {"supernodal", LinearSolver::kSupernodal}};
constexpr EnumName<slam::BlanketPolicy> kBlankets[] = {
    {"factors_at_node", slam::BlanketPolicy::kFactorsAtK},
    {"markov_blanket", slam::BlanketPolicy::kBlanket}};

/// Keys that look like settings but are deliberately not in the file.
const std::map<std::string, std::string>& Hints() {
  static const std::map<std::string, std::string> hints = {
      {"pruning.mode", "the pruning mode is chosen with --modes, not in the config"},
      {"loops.matcher.linear_window_m", "set per attempt from loops.min_window_m..max_window_m"},
      {"loops.matcher.angular_window_rad",
       "set per attempt from loops.min_window_rad..max_window_rad"},
      {"optimizer.anchor", "the mapper always anchors the oldest node"}};
  return hints;
}

// ---- Every setting, once. The reader and the writer both walk these lists. ----

template <class V>
void VisitMatcher(V& v, slam::MatcherConfig& m, bool with_windows) {
  if (with_windows) {
    v.Number("linear_window_m", m.linear_window_m, kPositive);
    v.Number("angular_window_rad", m.angular_window_rad, kPositive);
  }
  v.Number("resolution_m", m.resolution_m, kPositive);
  v.Number("angular_step_rad", m.angular_step_rad, kNonNegative);
  v.PowerOfTwo("coarse_factor", m.coarse_factor);
  v.Number("sigma_m", m.sigma_m, kPositive);
  v.Number("min_score", m.min_score, kUnit);
  v.Number("ambiguity_radius_m", m.ambiguity_radius_m, kNonNegative);
  v.Number("ambiguity_angle_rad", m.ambiguity_angle_rad, kNonNegative);
  v.Number("floor_sigma_m", m.floor_sigma_m, kNonNegative);
  v.Number("floor_sigma_rad", m.floor_sigma_rad, kNonNegative);
}

template <class V>
void VisitIncremental(V& v, slam::IncrementalConfig& c) {
  v.Int("local_map_nodes", c.local_map_nodes, 1);
  v.Number("point_spacing_m", c.point_spacing_m, kNonNegative);
  v.Section("matcher", [&](auto& s) { VisitMatcher(s, c.matcher, true); });
  v.Number("odom_sigma_xy_m", c.odom_sigma_xy_m, kPositive);
  v.Number("odom_sigma_xy_per_m", c.odom_sigma_xy_per_m, kNonNegative);
  v.Number("odom_sigma_rad", c.odom_sigma_rad, kPositive);
  v.Number("odom_sigma_rad_per_rad", c.odom_sigma_rad_per_rad, kNonNegative);
}

template <class V>
void VisitVerify(V& v, slam::LoopVerifierConfig& c) {
  v.Bool("enabled", c.enabled);
  v.Int("min_group", c.min_group, 1);
  v.Number("consistency_chi2", c.consistency_chi2, kPositive);
  v.Number("window_m", c.window_m, kNonNegative);
  v.Number("expiry_m", c.expiry_m, kNonNegative);
  v.Number("base_var_xy_m2", c.base_var_xy_m2, kPositive);
  v.Number("var_xy_per_m", c.var_xy_per_m, kNonNegative);
  v.Number("base_var_rad2", c.base_var_rad2, kPositive);
  v.Number("var_rad_per_m", c.var_rad_per_m, kNonNegative);
}

template <class V>
void VisitLoops(V& v, slam::LoopClosingConfig& c) {
  v.Bool("enabled", c.enabled);
  v.Number("min_path_separation_m", c.min_path_separation_m, kNonNegative);
  v.Number("overlap_radius_m", c.overlap_radius_m, kNonNegative);
  v.Number("gate_chi2", c.gate_chi2, kPositive);
  v.Number("max_position_sigma_m", c.max_position_sigma_m, kPositive);
  v.Number("min_window_m", c.min_window_m, kPositive);
  v.Number("max_window_m", c.max_window_m, kPositive);
  v.Ordered("min_window_m", c.min_window_m, "max_window_m", c.max_window_m);
  v.Number("min_window_rad", c.min_window_rad, kPositive);
  v.Number("max_window_rad", c.max_window_rad, kPositive);
  v.Ordered("min_window_rad", c.min_window_rad, "max_window_rad", c.max_window_rad);
  v.Int("neighbours_per_candidate", c.neighbours_per_candidate, 0);
  v.Int("submap_span", c.submap_span, 0);
  v.Number("min_score", c.min_score, kUnit);
  v.Number("max_ambiguity", c.max_ambiguity, kUnit);
  v.Number("max_flatness", c.max_flatness, kUnit);
  v.Number("uniqueness_radius_m", c.uniqueness_radius_m, kPositive);
  v.Number("refine_window_m", c.refine_window_m, kNonNegative);
  v.Number("refine_window_rad", c.refine_window_rad, kPositive);
  v.Number("consistency_chi2", c.consistency_chi2, kPositive);
  v.Int("min_reference_points", c.min_reference_points, 0);
  v.Section("matcher", [&](auto& s) { VisitMatcher(s, c.matcher, false); });
  v.Number("optimize_edge_chi2", c.optimize_edge_chi2, kNonNegative);
  v.Int("optimize_every", c.optimize_every, 1);
  v.Section("verify", [&](auto& s) { VisitVerify(s, c.verify); });
  v.Number("suspect_chi2", c.suspect_chi2, kPositive);
  v.Number("inject_false_share", c.inject_false_share, kUnit);
  v.Number("inject_false_dx_m", c.inject_false_dx_m, kAnyNumber);
  v.Number("inject_false_dy_m", c.inject_false_dy_m, kAnyNumber);
}

template <class V>
void VisitOptimizer(V& v, slam::OptimizerParams& p) {
  v.Enum("method", p.method, kMethods);
  v.Int("max_iterations", p.max_iterations, 1);
  v.Number("relative_tolerance", p.relative_tolerance, kNonNegative);
  v.Number("step_tolerance", p.step_tolerance, kNonNegative);
  v.Number("absolute_tolerance", p.absolute_tolerance, kNonNegative);
  v.Enum("robust_kernel", p.robust_kernel, kKernels);
  v.Number("robust_delta", p.robust_delta, kPositive);
  v.Bool("scale_damping", p.scale_damping);
  v.Number("initial_lambda_factor", p.initial_lambda_factor, kPositive);
  v.Bool("evaluate_final_chi2", p.evaluate_final_chi2);
  v.Bool("linear_initialization", p.linear_initialization);
  v.Enum("linear_solver", p.linear_solver, kSolvers);
}

template <class V>
void VisitConfig(V& v, slam::MapperConfig& c) {
  v.Section("keyframes", [&](auto& s) {
    s.Number("min_translation_m", c.keyframes.min_translation_m, kNonNegative);
    s.Number("min_rotation_rad", c.keyframes.min_rotation_rad, kNonNegative);
  });
  v.Section("incremental", [&](auto& s) { VisitIncremental(s, c.incremental); });
  v.Section("loops", [&](auto& s) { VisitLoops(s, c.loops); });
  v.Section("pruning", [&](auto& s) {
    s.Number("gain_threshold_bits", c.pruning.gain_threshold_bits, kAnyNumber);
    s.Number("radius_m", c.pruning.radius_m, kNonNegative);
    s.Int("keep_recent_nodes", c.pruning.keep_recent_nodes, 0);
    s.Int("node_budget", c.pruning.node_budget, 0);
    s.Number("max_edges_per_node", c.pruning.max_edges_per_node, kNonNegative);
    s.Enum("blanket", c.pruning.blanket, kBlankets);
    s.Choice("policy", c.pruning.policy, slam::RemovalPolicyNames(), false);
    s.Choice("sparsifier", c.pruning.sparsifier, slam::SparsifierNames(), true);
  });
  v.Section("grid", [&](auto& s) {
    s.Number("resolution_m", c.grid.resolution_m, kPositive);
    s.Number("max_free_range_m", c.grid.max_free_range_m, kNonNegative);
    s.Number("max_hit_range_m", c.grid.max_hit_range_m, kPositive);
  });
  v.Section("optimizer", [&](auto& s) { VisitOptimizer(s, c.optimizer); });
  v.Section("map_update", [&](auto& s) {
    s.Number("map_move_epsilon_m", c.map_move_epsilon_m, kNonNegative);
    s.Number("map_move_epsilon_rad", c.map_move_epsilon_rad, kNonNegative);
  });
}

// ---- Reading: strict, every error an InputError with file, 1-based line and field. ----

/// Shortest text that reads back to exactly `v`, with a ".0" on integral values.
std::string ShortestDouble(double v) {
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof(buf), v);
  std::string s(buf, result.ptr);
  if (std::isfinite(v) && s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

int LineOf(const YAML::Node& node) {
  const int line = node.Mark().line;
  return line >= 0 ? line + 1 : 0;
}

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

  void Number(const char* key, double& value, const Range& range) {
    const YAML::Node n = Take(key);
    if (!n) return;
    double v = 0.0;
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, v)) {
      Fail(n, Name(key), "expected a number, got '" + Text(n) + "'");
    }
    const bool below = range.min_open ? v <= range.min : v < range.min;
    if (!std::isfinite(v) || below || v > range.max) {
      Fail(n, Name(key), std::string("must be ") + range.text + ", got " + Text(n));
    }
    value = v;
  }

  void Int(const char* key, int& value, int min) {
    const YAML::Node n = Take(key);
    if (!n) return;
    int v = 0;
    if (!n.IsScalar() || !YAML::convert<int>::decode(n, v)) {
      Fail(n, Name(key), "expected an integer, got '" + Text(n) + "'");
    }
    if (v < min) Fail(n, Name(key), "must be >= " + std::to_string(min) + ", got " + Text(n));
    value = v;
  }

  void PowerOfTwo(const char* key, int& value) {
    int v = value;
    Int(key, v, 1);
    const YAML::Node n = Node()[key];
    if (n && (v & (v - 1)) != 0) Fail(n, Name(key), "must be a power of 2, got " + Text(n));
    value = v;
  }

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

  /// One of `names` (or, with allow_empty, an empty string or nothing: "").
  void Choice(const char* key, std::string& value, const std::vector<std::string>& names,
              bool allow_empty) {
    const YAML::Node n = Take(key);
    if (!n) return;
    if (allow_empty && (n.IsNull() || (n.IsScalar() && n.Scalar().empty()))) {
      value.clear();
      return;
    }
    std::string choices;
    for (const std::string& name : names) {
      if (n.IsScalar() && n.Scalar() == name) {
        value = name;
        return;
      }
      choices += (choices.empty() ? "" : ", ") + name;
    }
    Fail(n, Name(key), "expected one of " + choices + ", got '" + Text(n) + "'");
  }

  /// lo <= hi once both are read; blames hi when the file gives it, else lo.
  void Ordered(const char* lo_key, double lo, const char* hi_key, double hi) {
    if (lo <= hi) return;
    const char* key = Node()[hi_key] ? hi_key : lo_key;
    Fail(Node()[key], Name(key),
         std::string(lo_key) + " (" + ShortestDouble(lo) + ") exceeds " + hi_key + " (" +
             ShortestDouble(hi) + ")");
  }

  /// Every key must be a known one, given once (yaml-cpp would silently keep the first).
  void RejectUnknown() const {
    std::set<std::string> seen;
    for (auto it = node_.begin(); it != node_.end(); ++it) {
      const std::string key = it->first.Scalar();
      if (!seen.insert(key).second) Fail(it->first, Name(key), "duplicate key");
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

slam::MapperConfig Apply(const YAML::Node& root, const std::string& name,
                         const slam::MapperConfig& base) {
  slam::MapperConfig config = base;
  if (!root || root.IsNull()) return config;
  if (!root.IsMap()) throw InputError(name, LineOf(root), "", "expected a map of sections");
  Reader reader(name, root, "");
  VisitConfig(reader, config);
  reader.RejectUnknown();
  return config;
}

// ---- Writing. ----

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
  void Int(const char* key, int value, int) { Put(key, std::to_string(value)); }
  void PowerOfTwo(const char* key, int value) { Put(key, std::to_string(value)); }
  void Bool(const char* key, bool value) { Put(key, value ? "true" : "false"); }
  template <class E, std::size_t N>
  void Enum(const char* key, E value, const EnumName<E> (&names)[N]) {
    for (const auto& [name, e] : names) {
      if (e == value) Put(key, name);
    }
  }
  void Choice(const char* key, const std::string& value, const std::vector<std::string>&, bool) {
    out_ << YAML::Key << key << YAML::Value << YAML::DoubleQuoted << value;
  }
  void Ordered(const char*, double, const char*, double) {}

 private:
  void Put(const char* key, const std::string& text) {
    out_ << YAML::Key << key << YAML::Value << text;
  }
  YAML::Emitter& out_;
};

}  // namespace

slam::MapperConfig LoadMapperConfigFromString(const std::string& yaml, const std::string& name,
                                              const slam::MapperConfig& base) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::ParserException& e) {
    throw InputError(name, e.mark.line + 1, "", "malformed YAML: " + e.msg);
  }
  return Apply(root, name, base);
}

slam::MapperConfig LoadMapperConfig(const std::string& path, const slam::MapperConfig& base) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "", "cannot open the config file");
  } catch (const YAML::ParserException& e) {
    throw InputError(path, e.mark.line + 1, "", "malformed YAML: " + e.msg);
  }
  return Apply(root, path, base);
}

std::string MapperConfigToYaml(const slam::MapperConfig& config) {
  slam::MapperConfig copy = config;
  YAML::Emitter out;
  out << YAML::BeginMap;
  Writer writer(&out);
  VisitConfig(writer, copy);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace lifelong::eval
