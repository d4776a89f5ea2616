// Removal policy "dpg": removal that keeps the news, after DPG-SLAM (Walcott-Bryant, Kaess,
// Johannsson and Leonard, "Dynamic Pose Graph SLAM: Long-term Mapping in Low Dynamic
// Environments", IROS 2012). DPG-SLAM compares the laser scans of a place taken at
// different times, marks the samples of the older scans that the newer ones show to be
// removed (or whose free space now holds an object), keeps only active samples in the map,
// and retires a pose from the active map when its scan has too few active samples left.
// Here, at each round the current scan is compared with every node within compare_radius_m,
// candidate or not (change_detection.hpp; a node of an unsettled loop closure is no
// candidate, yet its scan shows the past like any other). Two scans that agree too little
// are not compared (their poses may disagree), unless an older scan outside the front end's
// local map agrees with the current one and so vouches for its pose. Of the nodes compared:
//   - the candidate's outdated beams are retired: the mapper takes them out of the counting
//     grid, so the map, and every scan's information gain (seed eq. 5.11), follows the
//     present. A scan that shows a change is no longer measured against the past it
//     contradicts, so its gain counts the change as information;
//   - a candidate whose active beams fall below min_active_share of its returns goes first,
//     whatever its gain: its scan mostly shows a past state;
//   - otherwise the seed's rule (removal_policy_information_gain.cpp) picks the node.
// (DPG-SLAM keeps a retired pose in its full graph for the history; here the mode's
// sparsifier marginalizes it, as for any removal.)
#include <algorithm>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "slam/grid/beam_cut.hpp"
#include "slam/removal/removal_policy.hpp"

namespace lifelong::slam {
namespace {

class DpgPolicy final : public RemovalPolicy {
 public:
  explicit DpgPolicy(const RemovalPolicyConfig& config)
      : config_(config), seed_(MakeInformationGainPolicy(config)) {}
  std::string Name() const override { return "dpg"; }

  void BeginRound(const std::map<NodeId, double>& gains, const RoundView& view) override {
    doomed_.clear();
    const ScanAt now = view.scan(view.current);
    const double r = config_.dpg.compare_radius_m;
    const std::vector<NodeId> ids = r > 0.0 && view.within ? view.within(r) : view.nearby;
    // The current node is the newest: no round has compared it yet, so none has cut it.
    // Each node is judged once, at the lower of the two bars; which pass which is decided here.
    const double bar = config_.dpg.detection.min_agreement;
    ChangeDetectionConfig lower = config_.dpg.detection;
    lower.min_agreement = std::min(bar, config_.dpg.min_agreement_vouched);
    std::vector<std::pair<NodeId, ScanComparison>> judged;
    bool vouched = false;
    for (const NodeId id : ids) {
      judged.emplace_back(id, Judge(id, now, view, lower));
      vouched = vouched || (id < view.local_map_from && Agrees(judged.back().second, bar));
    }
    // A scan that agrees with an older one outside the front end's local map has its pose
    // right against the older map here: the others there are compared even where most of
    // what they share with it changed since (a room seen through its door, its furniture
    // moved), down to min_agreement_vouched.
    for (const auto& [id, c] : judged) {
      const bool compared = Agrees(c, bar) || (vouched && c.compared);
      Apply(id, compared ? c.outdated : std::vector<BeamCut>{}, gains, view);
    }
  }

  std::vector<SampleRetirement> TakeRetirements() override { return std::exchange(retired_, {}); }

  std::optional<NodeId> Next(const std::map<NodeId, double>& gains,
                             std::size_t num_nodes) const override {
    for (NodeId id : doomed_) {
      if (gains.count(id)) return id;
    }
    return seed_->Next(gains, num_nodes);
  }

 private:
  /// Node id's scan compared with the current one.
  static ScanComparison Judge(NodeId id, const ScanAt& now, const RoundView& view,
                              const ChangeDetectionConfig& detection) {
    const ScanAt old = view.scan(id);
    // The older scan whole: a beam cut before still saw through a doorway, so it still
    // judges its neighbours and joins their run (a change is cut a few beams at a time,
    // from each pose that sees part of it).
    return CompareScans(*old.scan, old.T_world_robot, *now.scan, now.T_world_robot, detection);
  }
  /// Node id's `outdated` beams are retired, and it is doomed when too few are left.
  void Apply(NodeId id, const std::vector<BeamCut>& outdated, const std::map<NodeId, double>& gains,
             const RoundView& view) {
    const ScanAt old = view.scan(id);
    // A beam cut before is cut again only where the new verdict takes out more, by more
    // than edge_guard_m (a beam through a doorway whose far return went, then the door
    // closed).
    const std::vector<BeamCut> fresh =
        Tighter(*old.cut, outdated, config_.dpg.detection.edge_guard_m);
    // A beam retired: its return gone. A beam an object now crosses keeps its return.
    const std::vector<BeamCut> after = MergeCuts(*old.cut, fresh);
    const auto retired = static_cast<double>(
        std::count_if(after.begin(), after.end(), [](const BeamCut& b) { return !b.Resumes(); }));
    if (!fresh.empty()) retired_.push_back({id, fresh});
    const double returns = Returns(*old.scan);
    if (retired > 0 && gains.count(id) &&
        returns - retired < config_.dpg.min_active_share * returns) {
      doomed_.push_back(id);
    }
  }
  static double Returns(const LaserScan& scan) {
    int n = 0;
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) n += scan.IsReturn(i) ? 1 : 0;
    return n;
  }
  /// The cuts of `outdated` (ascending) that take out more than `cut` (ascending) does: a
  /// beam not cut yet, or one whose merged cut (Merge) ends its free space, or resumes it,
  /// more than `slack_m` away from where its cut does, or no longer resumes. A verdict a few
  /// centimetres off an earlier one (pose noise) would retrace the scan for nothing.
  static std::vector<BeamCut> Tighter(const std::vector<BeamCut>& cut,
                                      const std::vector<BeamCut>& outdated, double slack_m) {
    std::vector<BeamCut> out;
    auto k = cut.begin();
    for (const BeamCut& b : outdated) {
      while (k != cut.end() && k->beam < b.beam) ++k;
      if (k == cut.end() || k->beam != b.beam) {
        out.push_back(b);
        continue;
      }
      const BeamCut m = Merge(*k, b);
      if (m.Resumes() != k->Resumes() || k->free_to_m - m.free_to_m > slack_m ||
          m.resume_m - k->resume_m > slack_m) {
        out.push_back(b);
      }
    }
    return out;
  }

  RemovalPolicyConfig config_;
  std::unique_ptr<RemovalPolicy> seed_;  ///< information-gain, for the scans that show no change
  std::vector<NodeId> doomed_;           ///< this round's, in id order
  std::vector<SampleRetirement> retired_;
};

}  // namespace

std::unique_ptr<RemovalPolicy> MakeDpgPolicy(const RemovalPolicyConfig& config) {
  return std::make_unique<DpgPolicy>(config);
}

}  // namespace lifelong::slam
