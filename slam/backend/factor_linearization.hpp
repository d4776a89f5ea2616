// The Hessian (and gradient) of a single factor scattered into a local system over a list of
// nodes: the back-end builds its normal equations from them, and marginalization (seed §5.3,
// step 1) its H over a node's Markov blanket.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam {

/// Adds J^T Omega J of `edge` into H; node n occupies block index.at(n) (rows 3*index).
void AddEdgeHessian(const PoseEdge& edge, const Values& values, const std::vector<NodeId>& index,
                    Eigen::MatrixXd* H);
/// Adds J^T Lambda J of the stacked root-relative errors of `clique` (pose_graph.hpp).
void AddCliqueHessian(const CliqueFactor& clique, const Values& values,
                      const std::vector<NodeId>& index, Eigen::MatrixXd* H);
/// A clique factor over k + 1 nodes linearized at their poses (`poses[u]` for clique.nodes[u]).
/// J is block-sparse (block row j: the root's Jacobian R_j and node j+1's N_j), so the blocks
/// of H = J^T Lambda J and g = J^T Lambda e come in O(k^2), not the O(k^3) of dense products:
///   H_00 = R^T Lambda R,  H_0,b+1 = R^T Lambda_:b N_b,  H_a+1,b+1 = N_a^T Lambda_ab N_b.
/// Members u: 0 is the root, j + 1 is node j. The back-end and AddCliqueLinearized share it.
struct CliqueLinearization {
  Eigen::MatrixXd R;                      ///< the root's Jacobian blocks, stacked (3k x 3)
  std::vector<Eigen::Matrix3d> N;         ///< node j+1's Jacobian (block row j only)
  Eigen::MatrixXd lambda_r;               ///< Lambda R
  std::vector<Eigen::MatrixXd> lambda_n;  ///< Lambda's block column j times N_j
  Eigen::VectorXd e;                      ///< the stacked errors (empty without the gradient)
  Eigen::VectorXd w;                      ///< Lambda e (empty without the gradient)
  Eigen::Matrix3d H(std::size_t u, std::size_t v) const;
  Eigen::Vector3d g(std::size_t u) const;  ///< needs the gradient
};
CliqueLinearization LinearizeCliqueFactor(const CliqueFactor& clique,
                                          const std::vector<Pose2>& poses, bool gradient);
/// AddCliqueHessian, and J^T Lambda e into g when g is not null (e: the clique's stacked
/// errors at `values`), through CliqueLinearization. Returns e^T Lambda e, the factor's chi2
/// (0 without g).
double AddCliqueLinearized(const CliqueFactor& clique, const Values& values,
                           const std::vector<NodeId>& index, Eigen::MatrixXd* H,
                           Eigen::VectorXd* g);

}  // namespace lifelong::slam
