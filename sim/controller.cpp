#include "sim/controller.hpp"

#include <algorithm>
#include <cmath>

namespace lifelong::sim {
namespace {

constexpr double kTurnInPlaceRad = 0.5;  // heading error above which the robot stops to turn
constexpr double kHeadingGain = 2.0;     // 1/s

double Approach(double from, double to, double max_step) {
  return from + std::clamp(to - from, -max_step, max_step);
}

}  // namespace

bool WaypointController::Reached(const Pose2& pose, const Point& target) const {
  return std::hypot(target.x - pose.x, target.y - pose.y) < robot_.waypoint_tolerance_m;
}

DriveCommand WaypointController::Toward(const Pose2& pose, const Point& target,
                                        const DriveCommand& current, double dt_s) const {
  const double dx = target.x - pose.x, dy = target.y - pose.y;
  const double d = std::hypot(dx, dy);
  const double alpha = NormalizeAngle(std::atan2(dy, dx) - pose.theta);
  const double w_abs = std::min({robot_.max_turn_rate_radps, kHeadingGain * std::abs(alpha),
                                 std::sqrt(2.0 * robot_.max_turn_accel_radps2 * std::abs(alpha))});
  DriveCommand wanted;
  wanted.w_radps = std::copysign(w_abs, alpha);
  const double align = std::max(0.0, 1.0 - std::abs(alpha) / kTurnInPlaceRad);
  wanted.v_mps = align * std::min(robot_.max_speed_mps, std::sqrt(2.0 * robot_.max_accel_mps2 * d));
  return Limit(wanted, current, dt_s);
}

DriveCommand WaypointController::Brake(const DriveCommand& current, double dt_s) const {
  return Limit({}, current, dt_s);
}

DriveCommand WaypointController::Limit(const DriveCommand& wanted, const DriveCommand& current,
                                       double dt_s) const {
  return {Approach(current.v_mps, wanted.v_mps, robot_.max_accel_mps2 * dt_s),
          Approach(current.w_radps, wanted.w_radps, robot_.max_turn_accel_radps2 * dt_s)};
}

}  // namespace lifelong::sim
