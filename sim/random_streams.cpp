#include "sim/random_streams.hpp"

#include <cmath>

namespace lifelong::sim {

std::uint64_t DeriveSeed(std::uint64_t parent, std::uint64_t id) {
  std::uint64_t z = parent + (id + 1) * 0x9E3779B97F4A7C15ull;  // wraps modulo 2^64
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::mt19937_64 StreamRng(std::uint64_t scenario_seed, RandomStream stream) {
  return std::mt19937_64(DeriveSeed(scenario_seed, static_cast<std::uint64_t>(stream)));
}

double Uniform(std::mt19937_64* rng) { return static_cast<double>((*rng)() >> 11) * 0x1.0p-53; }

double Gaussian(std::mt19937_64* rng) {
  constexpr double kTwoPi = 6.28318530717958647692;
  const double u1 = 1.0 - Uniform(rng);  // (0, 1]
  const double u2 = Uniform(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

}  // namespace lifelong::sim
