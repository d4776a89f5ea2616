// The optimizer's view of a pose graph, shared by the parts of the back-end (optimizer.cpp,
// optimizer_system, optimizer_lago): dense node indices, the column block of each free node
// and the place of every 3x3 block of H in the upper-triangular CSC value array; the
// objective (robust kernels, chi2) and the updates of the poses the layout points to.
// Internal to slam: the API is slam/backend/optimizer.hpp.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "sensor/pose2.hpp"
#include "slam/backend/optimizer.hpp"
#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam::backend {

constexpr int kNoBlock = -1;

// Robust kernels on s = e^T Omega e (slam/backend/optimizer.hpp): cost rho(s) and IRLS weight
// rho'(s).
struct KernelValue {
  double cost;
  double weight;
};

inline KernelValue ApplyKernel(double s, bool robust, const OptimizerParams& params) {
  const double d2 = params.robust_delta * params.robust_delta;
  if (!robust || params.robust_kernel == RobustKernel::kNone) return {s, 1.0};
  if (params.robust_kernel == RobustKernel::kHuber) {
    if (s <= d2) return {s, 1.0};
    const double r = std::sqrt(s);
    return {2.0 * params.robust_delta * r - d2, params.robust_delta / r};
  }
  if (params.robust_kernel == RobustKernel::kDcs) {  // Phi = d^2 (optimizer.hpp)
    if (s <= d2) return {s, 1.0};
    const double scale = 2.0 * d2 / (d2 + s);
    return {d2 * (3.0 * s - d2) / (s + d2), scale * scale};
  }
  return {d2 * std::log1p(s / d2), 1.0 / (1.0 + s / d2)};  // Cauchy
}

// Problem layout: dense node indices, column blocks and the position of every 3x3 block of
// H inside the upper-triangular CSC value array (H_ab with a <= b is stored in block
// column b; `rank` is a's position among the row blocks of that column, the diagonal last).
struct EdgeSlot {
  const PoseEdge* edge;
  int i, j;  // dense node indices
  int rank_ii, rank_jj, rank_ij;
};

struct CliqueSlot {
  const CliqueFactor* clique;
  std::vector<int> nodes;  // dense node indices, nodes[0] = root
  std::vector<int> ranks;  // for each pair (u <= v) of clique members, row-major upper
};

struct Layout {
  std::vector<Pose2*> poses;  // per dense node
  std::vector<int> block;     // per dense node: column block or kNoBlock
  std::vector<EdgeSlot> edges;
  std::vector<CliqueSlot> cliques;
  std::vector<std::vector<int>> rows_of_col;  // per block column b: row blocks a < b
  int num_blocks = 0;
};

/// The layout of `graph` over `values`, which must hold every node (std::invalid_argument
/// otherwise); `anchor` and nodes without factors get no column block.
Layout BuildLayout(const PoseGraph& graph, Values* values, NodeId anchor);

/// The objective at the current poses: sum of rho(e^T Omega e) over edges (robust ones
/// through params' kernel) and e^T Omega e over clique factors.
double Chi2(const Layout& layout, const OptimizerParams& params);

/// x <- x + dx for every node with a column block, the angle normalized.
void ApplyStep(const Layout& layout, const Eigen::VectorXd& dx);

/// The poses the layout points to, to put back with Restore.
std::vector<Pose2> Snapshot(const Layout& layout);
void Restore(const Layout& layout, const std::vector<Pose2>& saved);

}  // namespace lifelong::slam::backend
