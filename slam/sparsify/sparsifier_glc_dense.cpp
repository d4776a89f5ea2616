// Sparsifier "glc-dense": the exact marginal as one root-shifted GLC factor (glc.hpp steps 1-3).
// Linearizes k's clique itself (with the factors among N under BlanketPolicy::kBlanket, as
// GLC removes intra-clique factors), so it also replaces earlier GLC factors within N. A
// connected set of removed nodes goes at once (set_marginal.hpp), absorbing the factors among
// its whole boundary.
#include "slam/marginal/glc.hpp"
#include "slam/sparsify/set_marginal.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class GlcDenseSparsifier final : public Sparsifier {
 public:
  explicit GlcDenseSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "glc-dense"; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    Replacement r;
    CliqueMarginal m;
    if (MarginalToReplace(config_, graph, values, k, &r, &m)) Fill(values, m, &r);
    return r;
  }
  bool ReplacesSets() const override { return true; }
  std::optional<Replacement> ReplaceSet(const PoseGraph& graph, const Values& values,
                                        const std::vector<NodeId>& set) const override {
    const bool within = config_.blanket == BlanketPolicy::kBlanket;
    std::optional<SetMarginal> m = MarginalizeSet(graph, values, set, within);
    if (!m) return std::nullopt;
    Replacement r;
    r.neighbours = m->boundary;
    r.absorb_edges_within = r.absorb_cliques_within = within;
    Fill(values, m->marginal, &r);
    return r;
  }

 private:
  /// r's factors: the exact marginal m over r's neighbours as one GLC factor, moved as asked.
  void Fill(const Values& values, const CliqueMarginal& m, Replacement* r) const {
    GlcFactors f = GlcDense(r->neighbours, values, m.lambda_N, config_.eigen_tolerance);
    SetFactors(config_, values, m, std::move(f.edges), std::move(f.cliques), r);
    MoveMeans(config_.means, r->neighbours, values, m.lambda_N, m.g_N, m.chi2, &r->edges,
              &r->cliques);
  }
  SparsifierConfig config_;
};

}  // namespace

std::unique_ptr<Sparsifier> MakeGlcDenseSparsifier(const SparsifierConfig& config) {
  return std::make_unique<GlcDenseSparsifier>(config);
}

}  // namespace lifelong::slam
