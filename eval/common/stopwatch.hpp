// Wall time of a stretch of work, in seconds (steady clock).
#pragma once

#include <chrono>

namespace lifelong::eval {

using Clock = std::chrono::steady_clock;

/// Seconds since `since`.
inline double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

}  // namespace lifelong::eval
