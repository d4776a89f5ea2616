// Sparsifier "glc": Chow-Liu tree of root-shifted GLC factors (glc.hpp steps 1, 2 and 4).
// Linearizes k's clique itself (with the factors among N under BlanketPolicy::kBlanket, as
// GLC removes intra-clique factors), so it also replaces earlier GLC factors within N.
// When the tree is not definite on the marginal's informative directions (infinite KL), the
// dense GLC factor replaces it.
#include <cmath>

#include "slam/marginal/glc.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class GlcSparsifier final : public Sparsifier {
 public:
  explicit GlcSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "glc"; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    Replacement r;
    CliqueMarginal m;
    if (!MarginalToReplace(config_, graph, values, k, &r, &m)) return r;
    const double tol = config_.eigen_tolerance;
    GlcFactors f = GlcChowLiu(r.neighbours, values, m.lambda_N, tol, &r.regularized);
    SetFactors(config_, values, m, std::move(f.edges), std::move(f.cliques), &r);
    if (!std::isfinite(r.kl_divergence)) {
      // The tree misses informative directions of the marginal (a low-rank Lambda_y that
      // couples three or more relative poses at once, which no pairwise tree expresses):
      // keep the exact dense GLC factor instead, of the same (low) rank (issue #12).
      f = GlcDense(r.neighbours, values, m.lambda_N, tol);
      SetFactors(config_, values, m, std::move(f.edges), std::move(f.cliques), &r);
    }
    MoveMeans(config_.means, r.neighbours, values, m.lambda_N, m.g_N, m.chi2, &r.edges, &r.cliques);
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
