// Sparsifier "exact": one dense root-relative clique over N, the exact Schur complement (kExact).
// Wraps slam::Marginalize, so its factors are those of the mapper's matching mode.
#include "slam/marginalization.hpp"
#include "slam/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class ExactSparsifier final : public Sparsifier {
 public:
  explicit ExactSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "exact"; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    Replacement r = FromMarginalization(
        Marginalize(graph, values, k, MarginalizationMethod::kExact, BlanketPolicy::kFactorsAtK));
    KeepGradientIfAsked(config_, graph, values, k, false, false, &r);
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
