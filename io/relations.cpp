// Relations reader (Kümmerle et al. 2009); see relations.hpp.
#include "io/relations.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

double ParseNumber(const std::string& token, const std::string& path, int line, const char* field) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(v)) {
    throw InputError(path, line, field, "not a finite number: '" + token + "'");
  }
  return v;
}

}  // namespace

std::vector<Relation> ReadRelations(const std::string& path, double time_offset_s) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  static constexpr const char* kFields[] = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};
  std::vector<Relation> relations;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::istringstream tokens(text);
    std::string token;
    double v[8];
    int n = 0;
    while (tokens >> token) {
      if (n == 0 && token[0] == '#') break;
      if (n == 8) throw InputError(path, line, "", "more than 8 fields");
      v[n] = ParseNumber(token, path, line, kFields[n]);
      ++n;
    }
    if (n == 0) continue;
    if (n < 8)
      throw InputError(path, line, kFields[n],
                       "missing (line has " + std::to_string(n) + " of 8 fields)");
    relations.push_back({v[0] - time_offset_s, v[1] - time_offset_s, Pose2(v[2], v[3], v[7])});
  }
  return relations;
}

}  // namespace lifelong::io
