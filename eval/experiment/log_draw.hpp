// A draw of a recorded log (`replay --seed N`): one real run is one draw of a mapper whose
// outcome can hinge on one close score, so a figure from it has no interval. A draw perturbs
// each odometry step of the log by a small multiplicative noise, as if the same path had
// been driven with slightly different wheel slip, so that a sweep can replay a log under
// several seeds and give its figures with an interval, as it does for a simulated world.
// The scans and their stamps are untouched; so is the reference they are scored against.
#pragma once

#include <cstdint>
#include <vector>

#include "sensor/observation.hpp"

namespace lifelong::eval {

/// The noise of a draw, per odometry step Delta = (t, dtheta) between two observations:
///   t' = (1 + e_s) Rot(e_h) t,   dtheta' = (1 + e_t) dtheta + e_h,
/// e_s ~ N(0, scale_sigma), e_t ~ N(0, turn_sigma), e_h ~ N(0, heading_sigma_rad).
struct OdometryJitter {
  double scale_sigma = 0.01;          ///< of the step's length
  double turn_sigma = 0.01;           ///< of the step's turn
  double heading_sigma_rad = 0.0009;  ///< about 0.05 degrees per step
};

/// Replaces each observation's odometry pose by the composition of its perturbed steps from
/// the first observation's pose (which stays). A step with odometry_lost is no measurement
/// and stays as it is. The same seed gives the same stream on every machine (std::mt19937_64
/// and the simulator's Box-Muller, sim::Gaussian, not std::normal_distribution, whose output
/// the standard leaves to the library).
void DrawOdometry(std::uint64_t seed, const OdometryJitter& jitter,
                  std::vector<Observation>* stream);

}  // namespace lifelong::eval
