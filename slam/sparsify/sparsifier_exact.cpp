// Sparsifier "exact": one dense root-relative clique over N, the exact Schur complement (kExact).
// Wraps slam::Marginalize, so its factors are those of the mapper's matching mode. A connected
// set of removed nodes goes at once, through one sparse factorization (set_marginal.hpp).
#include "slam/marginal/marginalization.hpp"
#include "slam/sparsify/set_marginal.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class ExactSparsifier final : public Sparsifier {
 public:
  explicit ExactSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "exact"; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    Replacement r = FromMarginalization(MarginalizeExact(graph, values, k));
    KeepGradientIfAsked(config_, graph, values, k, false, false, &r);
    return r;
  }
  bool ReplacesSets() const override { return true; }
  std::optional<Replacement> ReplaceSet(const PoseGraph& graph, const Values& values,
                                        const std::vector<NodeId>& set) const override {
    std::optional<SetMarginal> m = MarginalizeSet(graph, values, set, false);
    if (!m) return std::nullopt;
    Replacement r;
    r.neighbours = m->boundary;
    r.cliques.push_back(ToCliqueFactor(r.neighbours, values, m->marginal.lambda_N));
    MoveMeans(config_.means, r.neighbours, values, m->marginal.lambda_N, m->marginal.g_N,
              m->marginal.chi2, &r.edges, &r.cliques);
    return r;
  }

 private:
  SparsifierConfig config_;
};

}  // namespace

std::unique_ptr<Sparsifier> MakeExactSparsifier(const SparsifierConfig& config) {
  return std::make_unique<ExactSparsifier>(config);
}

}  // namespace lifelong::slam
