// Progress lines with rate and ETA; see progress.hpp.
#include "eval/common/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <utility>

namespace lifelong::eval {

namespace {

// printf into a string, whole however long the text (a fixed buffer cut it short, and its
// length was taken from snprintf's count of what would have been written).
template <typename... Args>
std::string Printf(const char* format, Args... args) {
  const int n = std::snprintf(nullptr, 0, format, args...);
  if (n <= 0) return {};
  std::string text(static_cast<std::size_t>(n), '\0');
  std::snprintf(text.data(), text.size() + 1, format, args...);
  return text;
}

}  // namespace

std::string FormatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  const long s = std::lround(seconds);
  char buf[32];
  if (s < 60) {
    std::snprintf(buf, sizeof(buf), "%ld s", s);
  } else if (s < 3600) {
    std::snprintf(buf, sizeof(buf), "%ld:%02ld", s / 60, s % 60);
  } else {
    std::snprintf(buf, sizeof(buf), "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  }
  return buf;
}

ProgressMeter::ProgressMeter(std::ostream* out, double total, ProgressOptions options)
    : out_(out),
      total_(total),
      options_(std::move(options)),
      start_(Clock::now()),
      last_print_(start_) {}

std::string ProgressMeter::Line(double done, double covered_s, const std::string& detail) const {
  const double elapsed = elapsed_override_s_ >= 0.0
                             ? elapsed_override_s_
                             : std::chrono::duration<double>(Clock::now() - start_).count();
  const double fraction = total_ > 0.0 ? std::min(1.0, done / total_) : 1.0;
  std::string line = Printf("  %-13s %5.1f %%", options_.label.c_str(), 100.0 * fraction);
  if (elapsed > 0.0 && done > 0.0) {
    const double rate = done / elapsed;
    line += Printf("  %.1f %s/s", rate, options_.unit.c_str());
    if (covered_s > 0.0) line += Printf("  %.1fx real time", covered_s / elapsed);
    line += "  elapsed " + FormatDuration(elapsed);
    if (fraction < 1.0) line += "  ETA " + FormatDuration((total_ - done) / rate);
  }
  if (!detail.empty()) line += "  " + detail;
  return line;
}

void ProgressMeter::Print(double done, double covered_s, const std::string& detail) {
  const std::string line = Line(done, covered_s, detail);
  if (options_.terminal) {
    *out_ << "\r" << line << "\033[K" << std::flush;  // clear what a longer line left
  } else {
    *out_ << line << "\n" << std::flush;
  }
  last_print_ = Clock::now();
}

void ProgressMeter::Update(double done, double covered_s, const std::string& detail) {
  if (!out_ || finished_) return;
  const double fraction = total_ > 0.0 ? std::min(1.0, done / total_) : 1.0;
  if (options_.terminal) {
    const int percent = static_cast<int>(100.0 * fraction);
    const bool due = std::chrono::duration<double>(Clock::now() - last_print_).count() >= 0.2;
    if (percent != last_percent_ || due) {
      last_percent_ = percent;
      Print(done, covered_s, detail);
    }
    return;
  }
  const int decile = static_cast<int>(10.0 * fraction);
  if (decile > last_decile_ && decile > 0) {
    last_decile_ = decile;
    Print(done, covered_s, detail);
  }
}

void ProgressMeter::Finish(double covered_s, const std::string& detail) {
  if (!out_ || finished_) return;
  if (options_.terminal) {
    Print(total_, covered_s, detail);
    *out_ << "\n" << std::flush;
  } else if (last_decile_ < 10) {
    Print(total_, covered_s, detail);
  }
  finished_ = true;
}

}  // namespace lifelong::eval
