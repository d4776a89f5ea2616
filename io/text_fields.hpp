// Small helpers shared by the text formats of io/: strict number parsing with file:line
// errors, locale-independent fixed-point output, and rows of numeric fields.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace lifelong::io {

/// Parses the whole token as a finite number; InputError(path, line, field) otherwise.
double ParseFiniteNumber(const std::string& token, const std::string& path, int line,
                         const std::string& field);

/// Appends ' ' (unless *s is empty) and v with `decimals` digits, independent of the locale
/// (std::to_chars), so the same values always give the same bytes.
void AppendFixed(std::string* s, double v, int decimals);

/// Reads a whitespace-separated text file whose lines hold exactly fields.size() numbers;
/// blank lines and lines starting with '#' are skipped. Calls row(line_number, values) per
/// data line. Throws InputError naming the file, line and field on a missing file, a missing
/// or extra field, or a token that is not a finite number.
void ForEachNumericRow(const std::string& path, const std::vector<std::string>& fields,
                       const std::function<void(int, const std::vector<double>&)>& row);
/// Same, from a stream; `name` stands for the file in error messages. A value whose
/// magnitude exceeds its field's entry of `max_abs` (when given; sensor/input_bounds.hpp) is
/// an InputError too: corruption, not data.
void ForEachNumericRow(std::istream& in, const std::string& name,
                       const std::vector<std::string>& fields,
                       const std::function<void(int, const std::vector<double>&)>& row,
                       const std::vector<double>& max_abs = {});

}  // namespace lifelong::io
