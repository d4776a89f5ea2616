#include "eval/experiment/false_closures.hpp"

#include <cmath>
#include <memory>

#include "sensor/pose2.hpp"
#include "slam/mapping/mapper_config_fields.hpp"

namespace lifelong::eval {

std::optional<slam::ConfigProblem> Validate(const FalseClosureConfig& config) {
  if (!(config.share >= 0.0 && config.share <= 1.0)) {
    return slam::ConfigProblem{
        "false_closures.share",
        "must be in [0, 1], got " + slam::config_fields::ShortestDouble(config.share)};
  }
  if (!std::isfinite(config.dx_m) || !std::isfinite(config.dy_m)) {
    return slam::ConfigProblem{
        std::isfinite(config.dx_m) ? "false_closures.dy_m" : "false_closures.dx_m",
        "must be a finite number"};
  }
  return std::nullopt;
}

std::function<void(slam::LoopHypothesis*, const slam::Values&)> FalseClosureInjector(double share,
                                                                                     double dx_m,
                                                                                     double dy_m) {
  auto seen = std::make_shared<int>(0);
  return [=](slam::LoopHypothesis* h, const slam::Values& values) {
    const int n = (*seen)++;
    if (share <= 0.0 || std::floor((n + 1) * share) == std::floor(n * share)) return;
    const Pose2 matched = values.at(h->old) * h->T_old_current;
    const Pose2 moved(matched.x + dx_m, matched.y + dy_m, matched.theta);
    h->T_old_current = Between(values.at(h->old), moved);
    h->injected = true;
  };
}

}  // namespace lifelong::eval
