// Where a mapper step's time went, by stage (slam::StepStats, one row of timeline.csv).
#pragma once

namespace lifelong {

/// ms by stage, exclusive (what is left of the step's total is bookkeeping): incremental
/// matching and insertion of the new scan, loop closing (candidates, matching,
/// verification), the back-end alone, map updates after it, information gains,
/// marginalization and sparsification.
struct StageTimes {
  double match_ms = 0.0;
  double loop_ms = 0.0;
  double backend_ms = 0.0;
  double map_update_ms = 0.0;
  double gain_ms = 0.0;
  double marginalize_ms = 0.0;

  double Sum() const {
    return match_ms + loop_ms + backend_ms + map_update_ms + gain_ms + marginalize_ms;
  }
};

}  // namespace lifelong
