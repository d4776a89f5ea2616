#include "apps/cli_checks.hpp"

#include <cmath>
#include <filesystem>

namespace lifelong::apps {

CLI::Validator IntRange(int lo, int hi) {
  return CLI::Validator(
      [lo, hi](std::string& v) {
        int x = 0;
        if (!CLI::detail::lexical_cast(v, x) || x < lo || x > hi) {
          return "must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                 ", got " + v;
        }
        return std::string();
      },
      "INT in [" + std::to_string(lo) + ".." + std::to_string(hi) + "]");
}

CLI::Validator NotADirectory() {
  return CLI::Validator(
      [](std::string& path) {
        std::error_code ec;
        return std::filesystem::is_directory(path, ec) ? path + " is a directory, not a file"
                                                       : std::string();
      },
      "FILE");
}

CLI::Validator NonEmpty() {
  return CLI::Validator(
      [](std::string& v) { return v.empty() ? std::string("the path is empty") : std::string(); },
      "");
}

CLI::Validator FiniteNumber() {
  return CLI::Validator(
      [](std::string& v) {
        double x = 0.0;
        if (v.empty() || !CLI::detail::lexical_cast(v, x) || !std::isfinite(x)) {
          return "expected a finite number, got '" + v + "'";
        }
        return std::string();
      },
      "SECONDS");
}

std::optional<std::string> Unused(const CLI::Option* option, const std::string& needs) {
  if (option->count() == 0) return std::nullopt;
  return option->get_name() + " does nothing without " + needs;
}

}  // namespace lifelong::apps
