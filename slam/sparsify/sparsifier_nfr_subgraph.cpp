// Sparsifier "nfr-subgraph": nonlinear factor recovery (Mazuran et al., IJRR 2016) on the
// Chow-Liu tree plus at most floor(SparsifierConfig::nfr_chord_ratio * (m - 1)) more pairs
// (the strongest by the chow-liu pair weight among SparsifierConfig::nfr_chords: by default
// the pairs of N that pose edges joined before the removal, or every pair), with the
// KL-optimal informations found by projected Newton from the tree's closed form (nfr.hpp
// step 5). Its local KL is never above nfr-tree's on the same clique.
#include "slam/sparsify/nfr.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::slam {
namespace {

class NfrSubgraphSparsifier final : public Sparsifier {
 public:
  explicit NfrSubgraphSparsifier(const SparsifierConfig& config) : config_(config) {}
  std::string Name() const override { return "nfr-subgraph"; }
  Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const override {
    return NfrReplace(graph, values, k, config_, true);
  }

 private:
  SparsifierConfig config_;
};

}  // namespace

std::unique_ptr<Sparsifier> MakeNfrSubgraphSparsifier(const SparsifierConfig& config) {
  return std::make_unique<NfrSubgraphSparsifier>(config);
}

}  // namespace lifelong::slam
