#include "io/text_fields.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "sensor/input_error.hpp"

namespace lifelong::io {

double ParseFiniteNumber(const std::string& token, const std::string& path, int line,
                         const std::string& field) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(v)) {
    throw InputError(path, line, field, "not a finite number: '" + token + "'");
  }
  return v;
}

void AppendFixed(std::string* s, double v, int decimals) {
  char buf[512];
  const auto [end, ec] =
      std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  if (ec != std::errc()) throw std::invalid_argument("AppendFixed: cannot format a number");
  if (!s->empty()) s->push_back(' ');
  s->append(buf, end);
}

void ForEachNumericRow(const std::string& path, const std::vector<std::string>& fields,
                       const std::function<void(int, const std::vector<double>&)>& row) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  ForEachNumericRow(in, path, fields, row);
}

void ForEachNumericRow(std::istream& in, const std::string& name,
                       const std::vector<std::string>& fields,
                       const std::function<void(int, const std::vector<double>&)>& row,
                       const std::vector<double>& max_abs) {
  const std::size_t n_fields = fields.size();
  std::vector<double> values;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    if (line == std::numeric_limits<int>::max()) throw InputError(name, line, "", "too many lines");
    ++line;
    std::istringstream tokens(text);
    std::string token;
    values.clear();
    while (tokens >> token) {
      if (values.empty() && token[0] == '#') break;
      if (values.size() == n_fields) {
        throw InputError(name, line, "", "more than " + std::to_string(n_fields) + " fields");
      }
      const std::size_t i = values.size();
      const double v = ParseFiniteNumber(token, name, line, fields[i]);
      if (i < max_abs.size() && std::abs(v) > max_abs[i]) {
        std::ostringstream what;
        what << "'" << token << "' is beyond " << max_abs[i] << ": corrupt, not data";
        throw InputError(name, line, fields[i], what.str());
      }
      values.push_back(v);
    }
    if (values.empty()) continue;
    if (values.size() < n_fields) {
      throw InputError(name, line, fields[values.size()],
                       "missing (line has " + std::to_string(values.size()) + " of " +
                           std::to_string(n_fields) + " fields)");
    }
    row(line, values);
  }
  if (in.bad()) throw InputError(name, line, "", "read error");
}

}  // namespace lifelong::io
