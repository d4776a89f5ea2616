// Removal policy "overlap": the rule of slam_toolbox's lifelong mode (Macenski and Jambrecic,
// "SLAM Toolbox: SLAM for the dynamic world", JOSS 2021; src/experimental/
// slam_toolbox_lifelong.cpp), measured here beside the seed's information gain. Every node
// carries a score, 1 when it is made. At each round, every older candidate that overlaps the
// current scan is scored again from the two scans' axis-aligned bounding boxes:
//   IoU  = |A n B| / |A u B|, area = |A n B| / |B|, reading = share of B's returns in A n B,
//   (A the current scan's box, B the candidate's), with c the candidate's graph edges:
//   score = -1                                    when IoU > iou_match and c < 3,
//   score = s (1 + k) - o - nearby_penalty       otherwise, capped at 1, where
//     o = overlap_scale min(area, reading) and k = min(o, clamp(constraint_scale (c - 2), 0, 1)).
// Candidates with IoU < iou_min or fewer than 2 edges are left alone, and so are the newest
// scan_buffer scans. A score below removal_score removes the node: the newer scan wins, so
// the map follows the present. (slam_toolbox deletes the node and its constraints; here the
// mode's sparsifier marginalizes it, so only the choice of node differs from the seed's.)
#include <algorithm>
#include <map>
#include <vector>

#include "slam/removal/removal_policy.hpp"

namespace lifelong::slam {
namespace {

double Area(const Eigen::AlignedBox2d& b) { return b.isEmpty() ? 0.0 : b.volume(); }

class OverlapPolicy final : public RemovalPolicy {
 public:
  explicit OverlapPolicy(const RemovalPolicyConfig& config) : config_(config.overlap) {}
  std::string Name() const override { return "overlap"; }

  void BeginRound(const std::map<NodeId, double>& gains, const RoundView& view) override {
    doomed_.clear();
    const ScanFootprint now = view.footprint(view.current);
    const double radius = 0.5 * now.box.diagonal().norm();
    for (const auto& [id, gain] : gains) {
      if (view.current - id < config_.scan_buffer) continue;
      const ScanFootprint old = view.footprint(id);
      if ((old.centre - now.centre).norm() > radius || old.edges < 2) continue;
      const double overlap_area = Area(now.box.intersection(old.box));
      const double iou = overlap_area / (Area(now.box) + Area(old.box) - overlap_area);
      if (!(iou >= config_.iou_min)) continue;
      const double score = Score(iou, overlap_area, now.box, old, Score(id));
      if (score < config_.removal_score) {
        doomed_.push_back(id);
      } else {
        scores_[id] = score;
      }
    }
  }

  std::optional<NodeId> Next(const std::map<NodeId, double>& gains, std::size_t) const override {
    for (NodeId id : doomed_) {
      if (gains.count(id)) return id;
    }
    return std::nullopt;
  }

  void Forget(NodeId id) override { scores_.erase(id); }

 private:
  double Score(NodeId id) const {
    const auto it = scores_.find(id);
    return it == scores_.end() ? 1.0 : it->second;
  }

  double Score(double iou, double overlap_area, const Eigen::AlignedBox2d& now,
               const ScanFootprint& old, double initial) const {
    if (iou > config_.iou_match && old.edges < 3) return -1.0;
    const double area = Area(old.box) > 0.0 ? overlap_area / Area(old.box) : 0.0;
    const Eigen::AlignedBox2d inside = now.intersection(old.box);
    std::size_t in = 0;
    for (const Eigen::Vector2d& p : old.points) in += inside.contains(p) ? 1 : 0;
    const double reading =
        old.points.empty() ? 0.0 : static_cast<double>(in) / static_cast<double>(old.points.size());
    const double o = config_.overlap_scale * std::min(area, reading);
    const double k = std::min(o, std::clamp(config_.constraint_scale * (old.edges - 2), 0.0, 1.0));
    return std::min(1.0, initial * (1.0 + k) - o - config_.nearby_penalty);
  }

  OverlapRuleConfig config_;
  std::map<NodeId, double> scores_;  ///< nodes scored at least once; the others are at 1
  std::vector<NodeId> doomed_;       ///< this round's, in id order
};

}  // namespace

std::unique_ptr<RemovalPolicy> MakeOverlapPolicy(const RemovalPolicyConfig& config) {
  return std::make_unique<OverlapPolicy>(config);
}

}  // namespace lifelong::slam
