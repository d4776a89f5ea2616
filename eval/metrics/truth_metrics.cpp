#include "eval/metrics/truth_metrics.hpp"

#include <memory>

#include "eval/metrics/map_quality.hpp"
#include "eval/metrics/metrics.hpp"
#include "eval/metrics/trajectory_reference.hpp"

namespace lifelong::eval {
namespace {

BlurSummary Summarize(const BlurResult& blur) {
  BlurSummary bs;
  if (blur.occupied_cells > 0) {
    bs.mean_cm = blur.mean_cm;
    bs.p95_cm = blur.p95_cm;
  }
  bs.thickness = blur.thickness;
  if (blur.wall_cells > 0) bs.recall = blur.recall;
  return bs;
}

}  // namespace

std::optional<RpeSummary> Rpe1m(const std::vector<Pose2>& estimate,
                                const std::vector<Pose2>& reference) {
  const DistanceRpe r = ComputeRpeAtDistance(estimate, reference, 1.0);
  if (r.count == 0) return std::nullopt;
  return RpeSummary{static_cast<std::int64_t>(r.count), r.trans_rmse_m, r.rot_rmse_deg};
}

Pose2 ScoreAgainstTruth(const std::vector<Pose2>& estimate, const std::vector<Pose2>& truth,
                        const GroundTruth* walls, const OccupancyGrid* map, ModeSummary* summary) {
  const AteResult ate = ComputeAte(estimate, truth);
  summary->ate_rmse_m = ate.rmse_m;
  summary->rpe_1m = Rpe1m(estimate, truth);
  const Pose2 T_truth_est = AlignSE2(estimate, truth);
  if (!walls || !map) return T_truth_est;
  std::shared_ptr<const TruthRaster> raster = walls->raster;
  if (!raster || !raster->Fits(*map)) {
    raster = std::make_shared<const TruthRaster>(*walls, truth, map->resolution_m);
  }
  summary->blur = Summarize(ComputeBlur(*map, *raster, raster->walls(), T_truth_est));
  if (!walls->gone.empty()) {
    summary->current_blur = Summarize(ComputeBlur(*map, *raster, raster->walls_now(), T_truth_est));
    summary->stale_cells = StaleShare(*map, *raster, T_truth_est);
  }
  return T_truth_est;
}

}  // namespace lifelong::eval
