// The mapper's config file refuses bad input with the file, line and dotted field: unknown
// keys, wrong types, values out of range, malformed YAML and missing files.
#include <gtest/gtest.h>

#include <string>

#include "eval/experiment/mapper_config_file.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

/// Loads `yaml` and expects an InputError naming the file, `line` and `field`, whose message
/// contains `text`.
void ExpectError(const std::string& yaml, int line, const std::string& field,
                 const std::string& text) {
  SCOPED_TRACE(yaml);
  try {
    LoadMapperConfigFromString(yaml, "bad.yaml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.yaml");
    EXPECT_EQ(e.line(), line);
    EXPECT_EQ(e.field(), field);
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

TEST(MapperConfigFile, UnknownKeysNameTheDottedField) {
  ExpectError("loops:\n  matcher:\n    sigma: 0.1\n", 3, "loops.matcher.sigma", "unknown key");
  ExpectError("grid: {resolution_m: 0.1}\npruning_radius: 3\n", 2, "pruning_radius", "unknown key");
  ExpectError("pruning:\n  mode: pruned\n", 2, "pruning.mode", "--modes");
  ExpectError("pruning:\n  policy: node-budget\n", 2, "pruning.policy", "POLICY+SPARSIFIER");
  ExpectError("pruning:\n  sparsifier: glc\n", 2, "pruning.sparsifier", "POLICY+SPARSIFIER");
  ExpectError("loops:\n  matcher: {linear_window_m: 1}\n", 2, "loops.matcher.linear_window_m",
              "per attempt");
  ExpectError("pruning:\n  radius_m: 1\n  radius_m: 2\n", 3, "pruning.radius_m", "duplicate key");
}

TEST(MapperConfigFile, WrongTypesAreRejected) {
  ExpectError("pruning:\n  radius_m: six\n", 2, "pruning.radius_m", "expected a number");
  ExpectError("pruning:\n  node_budget: 2.5\n", 2, "pruning.node_budget", "expected an integer");
  ExpectError("loops:\n  enabled: maybe\n", 2, "loops.enabled", "expected true or false");
  ExpectError("pruning: 3\n", 1, "pruning", "expected a section");
  ExpectError("grid:\n  resolution_m: [0.1]\n", 2, "grid.resolution_m", "expected a number");
  ExpectError("- 1\n- 2\n", 1, "", "expected a map");
  ExpectError("optimizer:\n\n  method: newton\n", 3, "optimizer.method", "lm, gn");
}

TEST(MapperConfigFile, OutOfRangeValuesAreRejected) {
  ExpectError("pruning:\n  radius_m: -1\n", 2, "pruning.radius_m", ">= 0");
  ExpectError("pruning:\n  node_budget: -1\n", 2, "pruning.node_budget", ">= 0");
  ExpectError("grid:\n  resolution_m: 0\n", 2, "grid.resolution_m", "in [0.005, 10] m");
  ExpectError("incremental:\n  matcher:\n    coarse_factor: 12\n", 3,
              "incremental.matcher.coarse_factor", "power of 2");
  ExpectError("incremental:\n  matcher:\n    coarse_factor: 0\n", 3,
              "incremental.matcher.coarse_factor", "power of 2");
  ExpectError("loops:\n  min_score: 1.5\n", 2, "loops.min_score", "in [0, 1]");
  // eval's own section, checked by the same range visitor as the mapper's.
  ExpectError("false_closures:\n  share: 1.5\n", 2, "false_closures.share",
              "must be in [0, 1], got 1.5");
  ExpectError("incremental:\n  matcher: {linear_window_m: 0}\n", 2,
              "incremental.matcher.linear_window_m", "in (0, 50] m");
  // Windows, heading steps and block sizes that exhausted memory (bad_alloc) are refused.
  ExpectError("incremental:\n  matcher: {linear_window_m: 1e6}\n", 2,
              "incremental.matcher.linear_window_m", "in (0, 50] m");
  ExpectError("incremental:\n  matcher: {angular_window_rad: 1e6}\n", 2,
              "incremental.matcher.angular_window_rad", "in (0, pi] rad");
  ExpectError("incremental:\n  matcher: {angular_step_rad: 1e-9}\n", 2,
              "incremental.matcher.angular_step_rad", "0 (automatic) or in [1e-4, 0.5] rad");
  ExpectError("incremental:\n  matcher: {coarse_factor: 1048576}\n", 2,
              "incremental.matcher.coarse_factor", "up to 1024");
  ExpectError("loops:\n  max_window_m: 1e6\n", 2, "loops.max_window_m", "in (0, 50] m");
  ExpectError("incremental:\n  point_spacing_m: 1e-9\n", 2, "incremental.point_spacing_m",
              "0 (no thinning) or in [0.005, 1] m");
  ExpectError("optimizer:\n  max_iterations: 0\n", 2, "optimizer.max_iterations", ">= 1");
  ExpectError("keyframes:\n  min_translation_m: .nan\n", 2, "keyframes.min_translation_m",
              "got nan");
  // max below min: blame max when the file gives it, else min.
  ExpectError("loops:\n  min_window_m: 0.5\n  max_window_m: 0.4\n", 3, "loops.max_window_m",
              "min_window_m (0.5) exceeds max_window_m (0.4)");
  ExpectError("loops:\n  min_window_rad: 0.9\n", 2, "loops.min_window_rad", "exceeds");
}

TEST(MapperConfigFile, MalformedYamlAndMissingFilesAreInputErrors) {
  // Line 3 is indented less than its siblings: yaml-cpp reports it there (0-based 2).
  ExpectError("pruning:\n  radius_m: 1\n node_budget: 2\n", 3, "", "malformed YAML");
  ExpectError("pruning: {radius_m: 1\n", 2, "", "malformed YAML");
  const std::string missing = std::string(LIFELONG_SOURCE_DIR) + "/configs/no_such_file.yaml";
  try {
    LoadMapperConfig(missing);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), missing);
    EXPECT_EQ(e.line(), 0);
  }
}

}  // namespace
}  // namespace lifelong::eval
