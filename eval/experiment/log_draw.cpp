#include "eval/experiment/log_draw.hpp"

#include <cmath>
#include <random>

#include "sim/random_streams.hpp"

namespace lifelong::eval {

void DrawOdometry(std::uint64_t seed, const OdometryJitter& jitter,
                  std::vector<Observation>* stream) {
  if (stream->empty()) return;
  std::mt19937_64 rng(seed);
  Pose2 recorded_before = stream->front().T_odom_robot;
  Pose2 drawn = recorded_before;
  for (std::size_t i = 1; i < stream->size(); ++i) {
    Observation& o = (*stream)[i];
    const Pose2 step = Between(recorded_before, o.T_odom_robot);
    recorded_before = o.T_odom_robot;
    Pose2 drawn_step = step;
    if (!o.odometry_lost) {
      const double e_s = jitter.scale_sigma * sim::Gaussian(&rng);
      const double e_t = jitter.turn_sigma * sim::Gaussian(&rng);
      const double e_h = jitter.heading_sigma_rad * sim::Gaussian(&rng);
      const double c = std::cos(e_h), s = std::sin(e_h);
      drawn_step = Pose2((1.0 + e_s) * (c * step.x - s * step.y),
                         (1.0 + e_s) * (s * step.x + c * step.y), (1.0 + e_t) * step.theta + e_h);
    }
    drawn = drawn * drawn_step;
    o.T_odom_robot = drawn;
  }
}

}  // namespace lifelong::eval
