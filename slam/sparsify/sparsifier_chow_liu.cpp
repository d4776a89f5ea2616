// Sparsifier "chow-liu": Chow-Liu tree of relative-pose edges with exact pair conditionals
// (kChowLiu). Wraps slam::Marginalize, so its factors are those of the mapper's matching mode.
#include "slam/marginal/marginalization.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class ChowLiuSparsifier final : public Sparsifier {
 public:
  explicit ChowLiuSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "chow-liu"; }
  bool LeavesTrees() const override { return true; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    Replacement r = FromMarginalization(MarginalizeChowLiu(graph, values, k, config_.blanket));
    KeepGradientIfAsked(config_, graph, values, k, r.absorb_edges_within, false, &r);
    return r;
  }

 private:
  SparsifierConfig config_;
};

}  // namespace

std::unique_ptr<Sparsifier> MakeChowLiuSparsifier(const SparsifierConfig& config) {
  return std::make_unique<ChowLiuSparsifier>(config);
}

}  // namespace lifelong::slam
