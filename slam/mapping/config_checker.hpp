// The range check of the settings the Visit* functions declare (mapper_config_fields.hpp),
// as one visitor: whoever declares fields that way validates them with it.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "slam/mapping/mapper_config.hpp"
#include "slam/mapping/mapper_config_fields.hpp"

namespace lifelong::slam::config_fields {

/// A visitor of the Visit* functions that records the first setting outside its range, by its
/// dotted name (prefix.key); Validate(MapperConfig) and eval's sections use it.
class Checker {
 public:
  explicit Checker(std::string prefix = "") : prefix_(std::move(prefix)) {}

  template <class F>
  void Section(const char* key, F&& visit) {
    if (problem_) return;
    Checker child(Name(key));
    visit(child);
    problem_ = child.problem_;
  }
  void Number(const char* key, double value, const Range& range) {
    if (!range.Admits(value)) {
      Fail(key, std::string("must be ") + range.text + ", got " + ShortestDouble(value));
    }
  }
  void Int(const char* key, int value, int min, int max = std::numeric_limits<int>::max()) {
    if (value < min)
      Fail(key, "must be >= " + std::to_string(min) + ", got " + std::to_string(value));
    if (value > max)
      Fail(key, "must be <= " + std::to_string(max) + ", got " + std::to_string(value));
  }
  void PowerOfTwo(const char* key, int value) {
    if (value < 1 || (value & (value - 1)) != 0 || value > 1024) {
      Fail(key, "must be a power of 2 up to 1024, got " + std::to_string(value));
    }
  }
  void Bool(const char*, bool) {}
  template <class E, std::size_t N>
  void Enum(const char*, E, const EnumName<E> (&)[N]) {}  // typed: always one of them
  void Ordered(const char* lo_key, double lo, const char* hi_key, double hi) {
    if (lo > hi) {
      Fail(hi_key, std::string(lo_key) + " (" + ShortestDouble(lo) + ") exceeds " + hi_key + " (" +
                       ShortestDouble(hi) + ")");
      if (problem_->counterpart.empty()) problem_->counterpart = Name(lo_key);
    }
  }

  const std::optional<ConfigProblem>& problem() const { return problem_; }

 private:
  std::string Name(const std::string& key) const {
    return prefix_.empty() ? key : prefix_ + "." + key;
  }
  void Fail(const char* key, std::string message) {
    if (!problem_) problem_ = ConfigProblem{Name(key), std::move(message)};
  }

  std::string prefix_;
  std::optional<ConfigProblem> problem_;
};

}  // namespace lifelong::slam::config_fields
