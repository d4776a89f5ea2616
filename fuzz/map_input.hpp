// The input format of fuzz_map, shared with tests/io/fuzz_regression_test.cpp: a map_server
// YAML, the separator line `@@PGM`, then the PGM bytes (no separator: YAML only).
#pragma once

#include <string>

namespace lifelong::fuzz {

inline constexpr char kMapSeparator[] = "\n@@PGM\n";

struct MapInput {
  std::string yaml;
  std::string pgm;
};

inline MapInput SplitMapInput(const std::string& bytes) {
  const std::size_t sep = bytes.find(kMapSeparator);
  if (sep == std::string::npos) return {bytes, ""};
  return {bytes.substr(0, sep), bytes.substr(sep + sizeof kMapSeparator - 1)};
}

}  // namespace lifelong::fuzz
