// The error factors hold at an estimate (CliqueChi2, FactorsChi2), and MoveMeans, which
// hands SparsifierConfig::means to PreserveGradient (sparsifier.cpp) with that bound.
#include <vector>

#include "slam/graph/se2.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

using Eigen::MatrixXd;
using Eigen::VectorXd;

double CliqueChi2(const CliqueFactor& c, const Values& values) {
  const VectorXd e =
      CliqueError(c, [&](std::size_t u) -> const Pose2& { return values.at(c.nodes[u]); });
  return e.dot(c.information * e);
}

double FactorsChi2(const Values& values, const std::vector<PoseEdge>& edges,
                   const std::vector<CliqueFactor>& cliques) {
  double chi2 = 0.0;
  for (const PoseEdge& e : edges) {
    chi2 += EdgeChi2(values.at(e.from), values.at(e.to), e.T_from_to, e.information);
  }
  for (const CliqueFactor& c : cliques) chi2 += CliqueChi2(c, values);
  return chi2;
}

void MoveMeans(FactorMeans means, const std::vector<NodeId>& nodes, const Values& values,
               const MatrixXd& lambda_N, const VectorXd& g_N, double chi2_replaced,
               std::vector<PoseEdge>* edges, std::vector<CliqueFactor>* cliques) {
  if (means == FactorMeans::kEstimate) return;
  PreserveGradient(nodes, values, g_N, edges, cliques,
                   means == FactorMeans::kMarginalMean ? &lambda_N : nullptr, chi2_replaced);
}

}  // namespace lifelong::slam
