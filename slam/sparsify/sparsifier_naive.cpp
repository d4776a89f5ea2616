// Sparsifier "naive": star of composed edges through k (marginalization.hpp, kNaive); ignores
// clique factors at k. Wraps slam::Marginalize, so its factors are those of the mapper's matching
// mode.
#include "slam/marginal/marginalization.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class NaiveSparsifier final : public Sparsifier {
 public:
  explicit NaiveSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "naive"; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    Replacement r = FromMarginalization(MarginalizeNaive(graph, values, k));
    KeepGradientIfAsked(config_, graph, values, k, false, false, &r);
    return r;
  }

 private:
  SparsifierConfig config_;
};

}  // namespace

std::unique_ptr<Sparsifier> MakeNaiveSparsifier(const SparsifierConfig& config) {
  return std::make_unique<NaiveSparsifier>(config);
}

}  // namespace lifelong::slam
