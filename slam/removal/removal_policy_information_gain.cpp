// Removal policy "information-gain": the seed's rule (§5.1). A scan whose gain is at or
// below the threshold adds (almost) nothing to the map, so its node goes, lowest first; with
// a node budget, the lowest also goes while the graph is over it.
#include "slam/removal/removal_policy.hpp"

namespace lifelong::slam {
namespace {

class InformationGainPolicy final : public RemovalPolicy {
 public:
  explicit InformationGainPolicy(const RemovalPolicyConfig& config) : config_(config) {}
  std::string Name() const override { return "information-gain"; }
  std::optional<NodeId> Next(const std::map<NodeId, double>& gains,
                             std::size_t num_nodes) const override {
    if (gains.empty()) return std::nullopt;
    const auto lowest = LowestGain(gains);
    const bool over_budget =
        config_.node_budget > 0 && num_nodes > static_cast<std::size_t>(config_.node_budget);
    if (lowest->second > config_.gain_threshold_bits && !over_budget) return std::nullopt;
    return lowest->first;
  }

 private:
  RemovalPolicyConfig config_;
};

}  // namespace

std::unique_ptr<RemovalPolicy> MakeInformationGainPolicy(const RemovalPolicyConfig& config) {
  return std::make_unique<InformationGainPolicy>(config);
}

}  // namespace lifelong::slam
