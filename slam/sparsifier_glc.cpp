// Sparsifier "glc": Chow-Liu tree of root-shifted GLC factors (glc.hpp steps 1, 2 and 4).
// Linearizes k's clique itself (with the factors among N under BlanketPolicy::kBlanket, as
// GLC removes intra-clique factors), so it also replaces earlier GLC factors within N.
// When the tree is not definite on the marginal's informative directions (infinite KL), the
// dense GLC factor replaces it.
#include <cmath>

#include "slam/glc.hpp"
#include "slam/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class GlcSparsifier final : public Sparsifier {
 public:
  explicit GlcSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "glc"; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    const bool within = config_.blanket == BlanketPolicy::kBlanket;
    const LocalSystem local = LinearizeClique(graph, values, k, within, within);
    Replacement r;
    r.neighbours = local.neighbours;
    if (r.neighbours.size() < 2) return r;  // a leaf drops out
    r.absorb_edges_within = r.absorb_cliques_within = within;
    Eigen::MatrixXd lambda_N;
    Eigen::VectorXd g_N;
    EliminateFirstBlock(local, &lambda_N, &g_N);
    const std::vector<NodeId>& nodes = r.neighbours;
    GlcFactors factors =
        GlcChowLiu(nodes, values, lambda_N, config_.eigen_tolerance, &r.regularized);
    r.edges = std::move(factors.edges);
    r.cliques = std::move(factors.cliques);
    r.kl_divergence = InformativeKl(lambda_N, FactorsHessian(nodes, values, r.edges, r.cliques),
                                    config_.eigen_tolerance);
    if (!std::isfinite(r.kl_divergence)) {
      // The tree misses informative directions of the marginal (a low-rank Lambda_y that
      // couples three or more relative poses at once, which no pairwise tree expresses):
      // keep the exact dense GLC factor instead, of the same (low) rank (issue #12).
      factors = GlcDense(nodes, values, lambda_N, config_.eigen_tolerance);
      r.edges = std::move(factors.edges);
      r.cliques = std::move(factors.cliques);
      r.kl_divergence = InformativeKl(lambda_N, FactorsHessian(nodes, values, r.edges, r.cliques),
                                      config_.eigen_tolerance);
    }
    if (config_.keep_gradient) PreserveGradient(nodes, values, g_N, &r.edges, &r.cliques);
    return r;
  }

 private:
  SparsifierConfig config_;
};

}  // namespace

std::unique_ptr<Sparsifier> MakeGlcSparsifier(const SparsifierConfig& config) {
  return std::make_unique<GlcSparsifier>(config);
}

}  // namespace lifelong::slam
