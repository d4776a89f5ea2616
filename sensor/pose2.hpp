// SE(2) rigid transforms. Naming: T_a_b maps points from frame b into frame a, so
// T_world_laser = T_world_robot * T_robot_laser.
#pragma once

#include <cmath>

namespace lifelong {

/// Wraps an angle into [-pi, pi).
inline double NormalizeAngle(double angle_rad) {
  constexpr double kPi = 3.14159265358979323846;
  double a = std::fmod(angle_rad + kPi, 2.0 * kPi);
  if (a < 0.0) a += 2.0 * kPi;
  return a - kPi;
}

/// A 2D pose / rigid transform: translation (m) and heading (rad, normalized).
struct Pose2 {
  double x = 0.0;      ///< m
  double y = 0.0;      ///< m
  double theta = 0.0;  ///< rad, in [-pi, pi)

  Pose2() = default;
  Pose2(double x_m, double y_m, double theta_rad)
      : x(x_m), y(y_m), theta(NormalizeAngle(theta_rad)) {}

  /// Composition: (this * other) applies `other` first, then `this`.
  Pose2 operator*(const Pose2& other) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * other.x - s * other.y, y + s * other.x + c * other.y, theta + other.theta};
  }

  Pose2 Inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, -theta};
  }

  /// Transforms a point given in this pose's frame into the parent frame.
  void Apply(double px, double py, double* out_x, double* out_y) const {
    const double c = std::cos(theta), s = std::sin(theta);
    *out_x = x + c * px - s * py;
    *out_y = y + s * px + c * py;
  }
};

/// Relative transform from a to b: Between(a, b) = a^-1 * b.
inline Pose2 Between(const Pose2& a, const Pose2& b) { return a.Inverse() * b; }

/// Length of a pose's translation, m.
inline double Norm(const Pose2& p) { return std::hypot(p.x, p.y); }

}  // namespace lifelong
