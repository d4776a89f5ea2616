// The colours of the graph's edge kinds, one palette for the video frames (render), the
// map PNGs (eval/figures/draw.cpp) and the report's legend, so that a figure reads the same in all.
#pragma once

#include <cstdint>

#include "types/edge_kind.hpp"

namespace lifelong::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

/// Odometry orange, loop closures magenta, marginal edges teal, priors grey.
constexpr Rgb EdgeColour(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kOdometry:
      return {255, 140, 0};
    case EdgeKind::kLoop:
      return {200, 0, 200};
    case EdgeKind::kMarginal:
      return {0, 170, 200};
    case EdgeKind::kPrior:
      return {128, 128, 128};
  }
  return {0, 0, 0};
}

/// Trajectories over the map PNGs: the true path green (drawn thin, under the graph),
/// odometry red, an estimate blue; graph nodes dark blue.
constexpr Rgb kTrueTrajectory{0, 160, 0};
constexpr Rgb kOdometryTrajectory{220, 0, 0};
constexpr Rgb kEstimateTrajectory{0, 0, 220};
constexpr Rgb kGraphNode{0, 40, 90};

}  // namespace lifelong::render
