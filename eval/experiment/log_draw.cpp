#include "eval/experiment/log_draw.hpp"

#include <cmath>
#include <random>

namespace lifelong::eval {
namespace {

/// Standard normal deviates from a generator whose sequence the standard fixes.
class Normal {
 public:
  explicit Normal(std::uint64_t seed) : engine_(seed) {}
  double Next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    constexpr double kTwoPi = 6.283185307179586;
    // (0, 1]: log(u1) is finite.
    const double u1 = (static_cast<double>(engine_() >> 11) + 1.0) * 0x1.0p-53;
    const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(kTwoPi * u2);
    has_spare_ = true;
    return r * std::cos(kTwoPi * u2);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace

void DrawOdometry(std::uint64_t seed, const OdometryJitter& jitter,
                  std::vector<Observation>* stream) {
  if (stream->empty()) return;
  Normal normal(seed);
  Pose2 recorded_before = stream->front().T_odom_robot;
  Pose2 drawn = recorded_before;
  for (std::size_t i = 1; i < stream->size(); ++i) {
    Observation& o = (*stream)[i];
    const Pose2 step = Between(recorded_before, o.T_odom_robot);
    recorded_before = o.T_odom_robot;
    Pose2 drawn_step = step;
    if (!o.odometry_lost) {
      const double e_s = jitter.scale_sigma * normal.Next();
      const double e_t = jitter.turn_sigma * normal.Next();
      const double e_h = jitter.heading_sigma_rad * normal.Next();
      const double c = std::cos(e_h), s = std::sin(e_h);
      drawn_step = Pose2((1.0 + e_s) * (c * step.x - s * step.y),
                         (1.0 + e_s) * (s * step.x + c * step.y), (1.0 + e_t) * step.theta + e_h);
    }
    drawn = drawn * drawn_step;
    o.T_odom_robot = drawn;
  }
}

}  // namespace lifelong::eval
