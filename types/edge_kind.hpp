// Where a pose-graph factor came from (slam), and a graph edge as drawn (render, eval).
#pragma once

#include <cstdint>

#include "types/segment.hpp"

namespace lifelong {

enum class EdgeKind : std::uint8_t {
  kOdometry,  ///< sequential: incremental scan matching / odometry
  kLoop,      ///< loop closure from scan matching against an older node
  kMarginal,  ///< produced by marginalizing a node out (Chow-Liu tree or naive composition)
  kPrior,     ///< unary-like edge, unused by the standard front-end
};

/// "odometry", "loop", "marginal" or "prior" (the names in summary.json's edges_by_kind).
constexpr const char* EdgeKindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kOdometry:
      return "odometry";
    case EdgeKind::kLoop:
      return "loop";
    case EdgeKind::kMarginal:
      return "marginal";
    case EdgeKind::kPrior:
      return "prior";
  }
  return "unknown";
}

/// A graph edge as drawn: its end points in the world frame (m) and its kind.
struct GraphEdge {
  Segment segment;
  EdgeKind kind = EdgeKind::kOdometry;
};

}  // namespace lifelong
