// The random streams of a simulation. A scenario's `seed` never seeds a generator itself:
// each kind of randomness draws from its own std::mt19937_64, seeded with
// DeriveSeed(seed, stream). Drawing more or fewer numbers from one stream (a longer tour,
// another place order) therefore leaves the others alone:
//   kRoute     tour destinations, drawn one leg at a time as the robot needs the next leg
//              (a draw that picks the place the robot is at is skipped).
//   kOdometry  wheel slip: two Gaussians per physics tick whatever the robot does, so the
//              slip of tick t depends only on the seed and t.
//   kLaser     range noise and dropout: scan k draws from a generator of its own, seeded with
//              DeriveSeed(DeriveSeed(seed, kLaser), k), one Gaussian and one uniform per beam
//              whether the beam hits or not, so beam i of scan k depends only on (seed, k, i).
#pragma once

#include <cstdint>
#include <random>

namespace lifelong::sim {

enum class RandomStream : std::uint64_t { kRoute = 0, kOdometry = 1, kLaser = 2 };

/// Seed of child `id` of `parent`: the (id + 1)-th output of SplitMix64 started at state
/// `parent` (Steele, Lea & Flood 2014; Vigna's splitmix64.c), i.e. the SplitMix64 mixer
/// applied to parent + (id + 1) * 0x9E3779B97F4A7C15. The mixer is a bijection with full
/// avalanche, so nearby seeds and ids give unrelated 64-bit seeds.
std::uint64_t DeriveSeed(std::uint64_t parent, std::uint64_t id);

/// Generator of one stream of a scenario seed.
std::mt19937_64 StreamRng(std::uint64_t scenario_seed, RandomStream stream);

/// Uniform sample in [0, 1) from the top 53 bits of one draw.
double Uniform(std::mt19937_64* rng);
/// Standard normal sample by Box-Muller from two 53-bit uniforms (portable across
/// standard libraries, unlike std::normal_distribution).
double Gaussian(std::mt19937_64* rng);

}  // namespace lifelong::sim
