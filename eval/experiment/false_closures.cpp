#include "eval/experiment/false_closures.hpp"

#include <cmath>
#include <memory>

#include "sensor/pose2.hpp"
#include "slam/mapping/config_checker.hpp"

namespace lifelong::eval {

std::optional<slam::ConfigProblem> Validate(const FalseClosureConfig& config) {
  slam::config_fields::Checker checker("false_closures");
  FalseClosureConfig values = config;  // the visitor takes the fields by reference
  VisitFalseClosures(checker, values);
  return checker.problem();
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
