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
//   overlap           slam_toolbox's lifelong rule (removal_policy_overlap.cpp): the newer of
//                     two overlapping scans wins; each older scan's score decays by its
//                     overlap with every new one, and it goes below a threshold
//   dpg               DPG-SLAM's rule (removal_policy_dpg.cpp): each new scan is compared
//                     with the older ones near it (change_detection.hpp); their beams that
//                     show a state the world has left are retired from the map, and a node
//                     with too few active beams left goes; otherwise the seed's rule
// Ties in gain go to the smaller id, so a run is reproducible.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <functional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/grid/change_detection.hpp"

namespace lifelong::slam {

/// The overlap rule's settings, slam_toolbox's `lifelong_*` parameters and defaults.
struct OverlapRuleConfig {
  double iou_min = 0.10;           ///< lifelong_minimum_score: less box overlap is no candidate
  double iou_match = 0.85;         ///< lifelong_iou_match: above, a candidate goes at once...
  double removal_score = 0.10;     ///< lifelong_node_removal_score: a score below it goes
  double overlap_scale = 0.5;      ///< lifelong_overlap_score_scale
  double constraint_scale = 0.05;  ///< lifelong_constraint_multiplier
  double nearby_penalty = 0.001;   ///< lifelong_nearby_penalty
  int scan_buffer = 10;            ///< Karto's scan_buffer_size: the newest scans keep their score
};

/// The DPG rule's settings (removal_policy_dpg.cpp).
struct DpgRuleConfig {
  ChangeDetectionConfig detection;
  /// A node whose active beams (returns not retired) fall below this share of its returns
  /// goes, whatever its gain: its scan mostly shows a past state.
  double min_active_share = 0.5;
  /// The current scan is compared with every node within this distance of it (m), not only
  /// with the round's candidates: an older scan taken farther off (from a corridor into a
  /// room) may have crossed what the current scan now sees standing, and its free beams
  /// would vote the new surface out of the map. The default is the grid's max_hit_range_m,
  /// as far as the map traces a return. 0: the round's radius only.
  double compare_radius_m = 12.0;
  /// Once the current scan agrees (detection.min_agreement) with a node outside the front
  /// end's local map, the other nodes it is compared with need only this share.
  double min_agreement_vouched = 0.0;
};

struct RemovalPolicyConfig {
  double gain_threshold_bits = 5.0;  ///< information-gain: remove at or below this
  int node_budget = 0;               ///< > 0: the most nodes the graph should hold
  OverlapRuleConfig overlap;
  DpgRuleConfig dpg;
};

/// A scan as the overlap rule sees it: its return points in the world frame, their
/// axis-aligned bounding box and centre, and its node's number of graph neighbours.
struct ScanFootprint {
  std::vector<Eigen::Vector2d> points;
  Eigen::AlignedBox2d box;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  int edges = 0;
};

/// A node's scan, the beams of it the map traces cut (BeamCut), and the node's pose.
struct ScanAt {
  const LaserScan* scan = nullptr;
  const std::vector<BeamCut>* cut = nullptr;  ///< ascending by beam
  Pose2 T_world_robot;
};

/// What a round shows a policy besides the gains: the current node, the nodes near it, and
/// any node's footprint and scan.
struct RoundView {
  NodeId current = 0;
  /// Every node within the round's radius but the current one, ascending: the candidates
  /// and the nodes no round removes (the newest, those of an unsettled loop closure). The
  /// scans of the latter still show the past a change outdates.
  std::vector<NodeId> nearby;
  /// Every node but the current one within a distance (m) of it, ascending, whatever the
  /// path between them.
  std::function<std::vector<NodeId>(double)> within;
  /// Nodes from this id on are in the front end's local map: the current scan was matched
  /// against them, so agreeing with them says nothing of its pose against the older map.
  NodeId local_map_from = 0;
  std::function<ScanFootprint(NodeId)> footprint;
  std::function<ScanAt(NodeId)> scan;
};

/// Beams of a node's scan that no longer show the world as far as they reach (a policy's
/// verdict): the mapper traces them cut (BeamCut) in the map from now on.
struct SampleRetirement {
  NodeId node = 0;
  std::vector<BeamCut> cuts;  ///< ascending by beam
};

class RemovalPolicy {
 public:
  virtual ~RemovalPolicy() = default;
  virtual std::string Name() const = 0;
  /// The candidate to remove next, or nullopt to stop. `gains` maps each candidate still
  /// in the round to its gain (bits); num_nodes is the graph's size now.
  virtual std::optional<NodeId> Next(const std::map<NodeId, double>& gains,
                                     std::size_t num_nodes) const = 0;
  /// Called once at the start of each round with its candidates (a policy that keeps state
  /// across rounds updates it here).
  virtual void BeginRound(const std::map<NodeId, double>& gains, const RoundView& view) {
    (void)gains, (void)view;
  }
  /// The beams this round's BeginRound found outdated, once (then cleared).
  virtual std::vector<SampleRetirement> TakeRetirements() { return {}; }
  /// A node left the graph.
  virtual void Forget(NodeId id) { (void)id; }
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
std::unique_ptr<RemovalPolicy> MakeOverlapPolicy(const RemovalPolicyConfig& config);
std::unique_ptr<RemovalPolicy> MakeDpgPolicy(const RemovalPolicyConfig& config);

}  // namespace lifelong::slam
