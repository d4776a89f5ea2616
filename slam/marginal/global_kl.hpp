// Global KL divergence of a sparsified graph (DESIGN.md "Methods as parts"; the measure of
// Carlevaris-Bianco et al. 2014 and Mazuran et al. 2016). p: the exact marginal of the full
// graph over the kept nodes; q: the sparsified graph. Both are linearized at the full
// graph's optimum x* (every factor, no robust kernel) and conditioned on the first kept node
// a (its increment held at 0). With d = 3 (kept - 1):
//   Lambda_p = H_KK - H_KR H_RR^-1 H_RK   (K: kept nodes but a, R: removed nodes)
//   Lambda_q = the sparsified graph's Hessian at x* over K
//   KL(p || q) = 1/2 [tr(Lambda_q Lambda_p^-1) - d + ln|Lambda_p| - ln|Lambda_q|]
//              + 1/2 delta^T Lambda_q delta
// where delta = mu_q - mu_p: the sparsified optimum of the kept nodes, moved rigidly so that
// a sits where x* has it, minus x* (additive x, y, theta as the optimizer's increments;
// angles wrapped). Dense over K: memory 8 d^2 bytes per matrix, time O(d^3).
#pragma once

#include <cstddef>

#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam {

struct GlobalKl {
  double kl = 0.0;            ///< nats, covariance + mean terms; +inf if Lambda_q is singular
  double mean_term = 0.0;     ///< nats, 1/2 delta^T Lambda_q delta
  double rms_offset_m = 0.0;  ///< RMS of |t_q - t*| over the kept nodes (after the move)
  std::size_t dimension = 0;  ///< d
};

/// `full` and `full_optimum`: the graph before sparsification at its optimum; `sparse` and
/// `sparse_optimum`: the sparsified graph (its nodes a subset of full's) at its optimum.
GlobalKl GlobalKlDivergence(const PoseGraph& full, const Values& full_optimum,
                            const PoseGraph& sparse, const Values& sparse_optimum);

}  // namespace lifelong::slam
