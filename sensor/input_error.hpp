// Errors in user input (world, scenario, log, graph files): they carry the file, the
// line (1-based, 0 when unknown) and the field, and the CLI maps them to exit code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace lifelong {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string field, const std::string& what)
      : std::runtime_error(Format(file, line, field, what)),
        file_(std::move(file)),
        line_(line),
        field_(std::move(field)) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }

 private:
  static std::string Format(const std::string& file, int line, const std::string& field,
                            const std::string& what) {
    std::string s = file;
    if (line > 0) s += ":" + std::to_string(line);
    if (!field.empty()) s += ": field '" + field + "'";
    return s + ": " + what;
  }
  std::string file_;
  int line_;
  std::string field_;
};

}  // namespace lifelong
