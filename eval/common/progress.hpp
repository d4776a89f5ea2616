// Progress of long work on stderr: percent, count, rate, times real time and ETA. On a
// terminal one line is redrawn in place (`\r`) at most every 0.2 s and at every whole
// percent; otherwise (a log file, CI) one plain line is printed per 10 %, with no `\r`.
#pragma once

#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <string>

namespace lifelong::eval {

struct ProgressOptions {
  std::string label;         ///< e.g. the mode name, "simulate"
  std::string unit = "obs";  ///< what `done` counts, for the rate
  bool terminal = false;     ///< redraw one line in place
};

class ProgressMeter {
 public:
  /// `total` units of work; `out` may be nullptr (quiet).
  ProgressMeter(std::ostream* out, double total, ProgressOptions options);

  /// `done` units finished, covering `covered_s` seconds of robot time; `detail` is
  /// appended (nodes, edges, ...). Prints only when the rules above say so.
  void Update(double done, double covered_s, const std::string& detail = "");
  /// Ends the line (terminal) or prints the 100 % line if not yet printed.
  void Finish(double covered_s, const std::string& detail = "");

  /// The line Update would print now (without `\r` or newline); for tests.
  std::string Line(double done, double covered_s, const std::string& detail) const;

 private:
  using Clock = std::chrono::steady_clock;
  void Print(double done, double covered_s, const std::string& detail);

  std::ostream* out_;
  double total_;
  ProgressOptions options_;
  Clock::time_point start_;
  Clock::time_point last_print_;
  int last_percent_ = -1;
  int last_decile_ = -1;
  bool finished_ = false;
  double elapsed_override_s_ = -1.0;

 public:
  /// Tests: pretend this much wall time has passed since the start.
  void SetElapsedForTest(double seconds) { elapsed_override_s_ = seconds; }
};

/// "1:05:03" / "4:07" / "12 s": a duration for humans.
std::string FormatDuration(double seconds);

}  // namespace lifelong::eval
