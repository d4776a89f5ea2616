// Removal policies: which node goes next (DESIGN.md "Methods as parts"). In each pruning
// round the mapper hands a policy the candidates near the current node with their scans'
// information gains (bits, seed §5.1 eq. 5.3: I(z_i) = H(m without z_i) - H(m)) and the
// graph's size; the policy names the node to remove next, or none to end the round. What
// replaces the removed node's clique is the sparsifier's business (sparsifier.hpp). One
// class per policy, each in its own file, chosen by name (MakeRemovalPolicy):
//   information-gain  the seed's rule: the lowest gain while it is <= gain_threshold_bits,
//                     and, with a node budget, also while the graph is over it
//   node-budget       the lowest gain while the graph holds more than node_budget nodes,
//                     whatever the gain (a fixed-size graph; gains only rank)
// Ties in gain go to the smaller id, so a run is reproducible.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "slam/pose_graph.hpp"

namespace lifelong::slam {

struct RemovalPolicyConfig {
  double gain_threshold_bits = 5.0;  ///< information-gain: remove at or below this
  int node_budget = 0;               ///< > 0: the most nodes the graph should hold
};

class RemovalPolicy {
 public:
  virtual ~RemovalPolicy() = default;
  virtual std::string Name() const = 0;
  /// The candidate to remove next, or nullopt to stop. `gains` maps each candidate still
  /// in the round to its gain (bits); num_nodes is the graph's size now.
  virtual std::optional<NodeId> Next(const std::map<NodeId, double>& gains,
                                     std::size_t num_nodes) const = 0;
};

/// The policy called `name`, or nullptr when none has that name.
std::unique_ptr<RemovalPolicy> MakeRemovalPolicy(const std::string& name,
                                                 const RemovalPolicyConfig& config);
/// Every known name, in the registry's order.
std::vector<std::string> RemovalPolicyNames();

// ---- Shared by the policy files. ----

/// The candidate with the lowest gain (the smaller id on a tie); gains must not be empty.
std::map<NodeId, double>::const_iterator LowestGain(const std::map<NodeId, double>& gains);

std::unique_ptr<RemovalPolicy> MakeInformationGainPolicy(const RemovalPolicyConfig& config);
std::unique_ptr<RemovalPolicy> MakeNodeBudgetPolicy(const RemovalPolicyConfig& config);

}  // namespace lifelong::slam
