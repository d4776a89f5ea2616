// The error factors hold at an estimate (CliqueChi2, FactorsChi2), and MoveMeans, which
// hands SparsifierConfig::means to PreserveGradient (sparsifier.cpp) with that bound.
#include <vector>

#include "slam/backend/clique_algebra.hpp"
#include "slam/graph/se2.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {

using clique::Block;
using Eigen::MatrixXd;
using Eigen::VectorXd;

double CliqueChi2(const CliqueFactor& c, const Values& values) {
  VectorXd e(c.information.rows());
  for (std::size_t j = 0; j + 1 < c.nodes.size(); ++j) {
    e.segment<3>(Block(j)) =
        RelativeError(values.at(c.nodes[0]), values.at(c.nodes[j + 1]), c.T_root_node[j]);
  }
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
