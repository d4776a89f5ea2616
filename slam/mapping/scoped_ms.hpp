// The mapper's stage timer (StepStats::stages): nested scopes, each counting only its own time.
#pragma once

#include <chrono>

namespace lifelong::slam {

/// Adds the wall time of its scope, in ms, to *total, less the time of the timers nested in
/// it, so that the per-stage times of StepStats never count a moment twice (the map update
/// inside the matching stage, say, is the gains' when it updates gains). Nothing when total
/// is null. `innermost` is the timers' stack top, kept by the caller.
class ScopedMs {
 public:
  ScopedMs(double* total, ScopedMs** innermost)
      : total_(total),
        innermost_(innermost),
        parent_(total ? *innermost : nullptr),
        start_(std::chrono::steady_clock::now()) {
    if (total_) *innermost_ = this;
  }
  ~ScopedMs() {
    if (!total_) return;
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
            .count();
    *total_ += ms - nested_ms_;
    if (parent_) parent_->nested_ms_ += ms;
    *innermost_ = parent_;
  }
  ScopedMs(const ScopedMs&) = delete;
  ScopedMs& operator=(const ScopedMs&) = delete;

 private:
  double* total_;
  ScopedMs** innermost_;
  ScopedMs* parent_;
  std::chrono::steady_clock::time_point start_;
  double nested_ms_ = 0.0;
};

}  // namespace lifelong::slam
