// Sparsifier "nfr-tree": nonlinear factor recovery (Mazuran et al., IJRR 2016) on the Chow-Liu
// tree of the clique: m - 1 relative-pose edges whose informations minimize the KL divergence
// from the exact marginal, in closed form (nfr.hpp step 4). On the same tree these are the
// chow-liu sparsifier's exact pair conditionals, so both give the same KL (to rounding).
#include "slam/sparsify/nfr.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class NfrTreeSparsifier final : public Sparsifier {
 public:
  explicit NfrTreeSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "nfr-tree"; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    return NfrReplace(graph, values, k, config_, false);
  }

 private:
  SparsifierConfig config_;
};

}  // namespace

std::unique_ptr<Sparsifier> MakeNfrTreeSparsifier(const SparsifierConfig& config) {
  return std::make_unique<NfrTreeSparsifier>(config);
}

}  // namespace lifelong::slam
