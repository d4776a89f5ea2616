// Removal policy "node-budget": a graph of a fixed size. While it holds more than
// node_budget nodes, the candidate whose scan adds least to the map (lowest information
// gain, seed §5.1) goes, whatever its gain; within the budget nothing goes. Without a budget
// (node_budget = 0) it never removes.
#include "slam/removal/removal_policy.hpp"

namespace lifelong::slam {
namespace {

class NodeBudgetPolicy final : public RemovalPolicy {
 public:
  explicit NodeBudgetPolicy(const RemovalPolicyConfig& config) : config_(config) {}
  std::string Name() const override { return "node-budget"; }
  std::optional<NodeId> Next(const std::map<NodeId, double>& gains,
                             std::size_t num_nodes) const override {
    if (gains.empty() || config_.node_budget <= 0 ||
        num_nodes <= static_cast<std::size_t>(config_.node_budget)) {
      return std::nullopt;
    }
    return LowestGain(gains)->first;
  }

 private:
  RemovalPolicyConfig config_;
};

}  // namespace

std::unique_ptr<RemovalPolicy> MakeNodeBudgetPolicy(const RemovalPolicyConfig& config) {
  return std::make_unique<NodeBudgetPolicy>(config);
}

}  // namespace lifelong::slam
