// The argument checks the commands share (CLI11 validators), so that a bad value is named at
// its option before any work.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace lifelong::apps {

/// An integer range that names its bounds readably (CLI::PositiveNumber prints the largest
/// double as a 300-digit number).
CLI::Validator IntRange(int lo, int hi);

/// An input file that is a directory is named as such before any work (the readers' streams
/// failed on it with a library message, as an internal error).
CLI::Validator NotADirectory();

/// A path option given as "" names nothing: said at the option, not as "." or a missing file.
CLI::Validator NonEmpty();

/// A number that must be given as one: "" (which CLI11 reads as 0), "nan" and "inf" are
/// refused.
CLI::Validator FiniteNumber();

/// An option that only means something beside another is refused alone, not ignored.
std::optional<std::string> Unused(const CLI::Option* option, const std::string& needs);

}  // namespace lifelong::apps
