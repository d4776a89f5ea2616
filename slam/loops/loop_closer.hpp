// Loop closing as a component (seed §4.3): propose -> verify -> accept. The mapper hands the
// closer a read-only view of the graph, the estimate and the nodes' scans; the closer searches,
// matches and verifies, and hands back the closures to put into the graph. It never changes
// the graph itself, so the mapper decides when to optimize.
//
// Two searches, both per observation:
//  - the local one (loop_closer.cpp): candidates are the nodes inside the current pose's
//    uncertainty, found by Dijkstra projection of covariances (slam/graph/dijkstra.hpp); the
//    current scan is matched in a window of 3 sigma against a submap of the candidates' scans;
//  - the global one (loop_closer_global.cpp, loops.global): where the local one closed
//    nothing, place descriptors (slam/loops/place_descriptor.hpp) propose the most similar earlier
//    places wherever the estimate puts them, each matched in a wide window. While a closure
//    it proposed waits for confirmation, the scan is matched instead where that closure puts
//    the robot (loop_closer_follow.cpp, loops.global.follow_m).
// A match must score, be unambiguous and locally unique, and be plausible; it then waits in
// the group verifier (slam/loops/loop_verifier.hpp) until others confirm it.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "slam/graph/dijkstra.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/loops/loop_attempt.hpp"
#include "slam/loops/loop_config.hpp"
#include "slam/loops/loop_verifier.hpp"
#include "slam/loops/node_reach.hpp"
#include "slam/loops/place_descriptor.hpp"
#include "slam/loops/place_index.hpp"
#include "slam/loops/surface_cache.hpp"
#include "slam/matching/incremental_config.hpp"
#include "slam/matching/node_data.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {

/// What the loop closer reads of the mapper (valid for one call).
struct LoopClosingView {
  const PoseGraph& graph;
  const Values& values;
  const NodeStore& nodes;
  const std::vector<NodeId>& recent;  ///< node ids in insertion order
};

/// Called with every hypothesis before verification, with the estimate (eval's false-closure
/// test moves some of them).
using HypothesisHook = std::function<void(LoopHypothesis*, const Values&)>;

class LoopCloser {
 public:
  LoopCloser(const LoopClosingConfig& loops, const IncrementalConfig& incremental);

  /// The local search around node `current` at the `observation`-th observation (0-based; it
  /// decides whether candidates beyond the largest window are searched, see
  /// loops.beyond_window_every). Returns the attempt (none when no candidate lies inside the
  /// gate) and appends the closures accepted to *accepted, in order.
  std::optional<LoopAttempt> SearchLocal(const LoopClosingView& view, NodeId current,
                                         int observation, std::vector<LoopHypothesis>* accepted);
  /// The global search (loops.global) when `search` (the local one closed nothing and this is
  /// a searching observation), or the match where a waiting closure by place puts the robot
  /// while one is followed (loops.global.follow_m); then indexes `current`'s place. Uses the
  /// projection of the last SearchLocal, which must have been for `current`.
  std::optional<LoopAttempt> SearchGlobal(const LoopClosingView& view, NodeId current, bool search,
                                          std::vector<LoopHypothesis>* accepted);
  /// A node left the graph (marginalized): its closures no longer count as evidence, and its
  /// cached surfaces and place go.
  void ForgetNode(NodeId id);

  void set_hypothesis_hook(HypothesisHook hook) { hook_ = std::move(hook); }
  const LoopVerifierStats& stats() const { return verifier_.stats(); }
  /// Hypotheses waiting for confirmation (their nodes must stay).
  const std::vector<LoopHypothesis>& pending() const { return verifier_.pending(); }

 private:
  /// Node id's points for a reference, in the world frame: its surfaces when loops.surfaces
  /// is set (and the incremental rule makes any), its return points otherwise.
  std::vector<Eigen::Vector2d> Reference(const LoopClosingView& view, NodeId id);
  /// Matches the current node's points against the submap's references around `guess`: the
  /// match when it has enough points in reach, scores, is unambiguous and locally unique;
  /// else nothing and *why. *measured: the match's score and ambiguity whenever one ran
  /// (else untouched). `query`, when given, is matched in place of the node's points (in its
  /// frame): the global search's near returns (loops.global.near_range_m).
  std::optional<MatchResult> MatchSubmap(const LoopClosingView& view,
                                         const std::set<NodeId>& submap, NodeId current,
                                         const Pose2& guess, const MatcherConfig& mc,
                                         MatchRefusal* why, MatchMeasure* measured,
                                         const std::vector<Eigen::Vector2d>* query = nullptr);
  /// A search window: 3 sigma of `variance`, clamped to [lo, hi].
  static double Clamp3Sigma(double variance, double lo, double hi);
  /// The returns a failed candidate is matched with again (loops.global.near_range_m): those
  /// within that range of the robot; none when it is 0.
  static std::vector<Eigen::Vector2d> NearReturns(const std::vector<Eigen::Vector2d>& points,
                                                  const GlobalLoopConfig& g);
  /// `mc` as the loop searches run it: nothing below loops.min_score passes, and unless
  /// loops.measure_low_scores the search stops there (MatcherConfig::cut_below_min_score).
  MatcherConfig Cutting(MatcherConfig mc) const;
  /// The match's correction of the current pose lies inside the consistency gate
  /// (loops.consistency_chi2) of `covariance` plus the match's own.
  bool Plausible(const LoopClosingView& view, const MatchResult& match, NodeId current,
                 const Eigen::Matrix3d& covariance) const;
  /// No pose uniqueness_radius_m away (8 directions, same heading) scores above
  /// max_flatness times the best.
  bool LocallyUnique(const MatchResult& match, const std::vector<Eigen::Vector2d>& points) const;
  /// The submap match measured again against node `old`'s scan alone
  /// (loops.refine_window_m); the submap match itself when that fails.
  MatchResult RefineAgainstNode(const LoopClosingView& view, NodeId old,
                                const std::vector<Eigen::Vector2d>& points,
                                const MatchResult& submap_match);
  /// The closure old -> current measured by `match`, proposed to the verifier; the closures
  /// it accepted are appended to *accepted, and their number returned.
  int Propose(const LoopClosingView& view, NodeId old, NodeId current, const MatchResult& match,
              std::vector<LoopHypothesis>* accepted);
  /// The points of `id`'s place: its own and its recent neighbours', in its frame.
  std::vector<Eigen::Vector2d> PlacePoints(const LoopClosingView& view, NodeId id) const;
  /// An earlier place the descriptor index proposes, and its match once verified.
  struct PlaceCandidate {
    NodeId id;
    PlaceComparison cmp;
    double lateral_m = 0.0;  ///< the query described from this far to its left (y)
    /// Where the current scan is matched from: at the place, turned by the descriptors'
    /// heading and moved back from the query's shifted origin.
    Pose2 guess;
    MatchResult match;
  };
  /// The loops.global.candidates places most similar to `place` (described from `points`)
  /// among those the robot has left (odometry path length), within the descriptor distance,
  /// most similar first. The query is also described from origins shifted sideways
  /// (loops.global.lateral_steps), since a polar descriptor changes with a lane's offset.
  std::vector<PlaceCandidate> SimilarPlaces(const LoopClosingView& view, NodeId current,
                                            const std::vector<Eigen::Vector2d>& points,
                                            const PlaceDescriptor& place) const;
  /// Each candidate matched around its guess; those that match and are
  /// plausible where the covariance projection reaches them. *why: the last refusal;
  /// attempt->old and ->measured: the best-scoring candidate's, refused or not (old: the most
  /// similar place when no score was measured).
  std::vector<PlaceCandidate> MatchCandidates(const LoopClosingView& view, NodeId current,
                                              const std::vector<Eigen::Vector2d>* near,
                                              const std::vector<PlaceCandidate>& candidates,
                                              const MatcherConfig& mc, MatchRefusal* why,
                                              LoopAttempt* attempt);
  std::optional<LoopAttempt> MatchPlaces(const LoopClosingView& view, NodeId current,
                                         const std::vector<Eigen::Vector2d>& points,
                                         const PlaceDescriptor& place,
                                         std::vector<LoopHypothesis>* accepted);
  /// The scan matched where the pending closure by place being followed puts the robot
  /// (loops.global.follow_m, loop_closer_follow.cpp); nothing when none is followed or no old
  /// node lies near there.
  std::optional<LoopAttempt> Follow(const LoopClosingView& view, NodeId current,
                                    std::vector<LoopHypothesis>* accepted);
  /// Starts following the closure just proposed for `current`, if it waits unconfirmed.
  void StartFollowing(const LoopClosingView& view, NodeId old, NodeId current);

  LoopClosingConfig config_;
  IncrementalConfig incremental_;  ///< for its surface rule and point spacing
  LoopVerifier verifier_;
  ReferenceGrid grid_;           ///< the matcher's table, rebuilt in place for each match
  ReferenceGrid approach_grid_;  ///< the approach test's table (approach_check.hpp)...
  NodeReach reach_;              ///< ...and the nodes' reaches it reads
  /// Surface points (robot frame) of the nodes the recent submaps used (64 nodes: 80 % of
  /// the lookups on Intel hit, against 83 % with 256 and 57 % with 32).
  SurfaceCache surfaces_{64};
  PlaceIndex places_;  ///< the nodes' place descriptors (loops.global)
  /// The pending closure by place being followed, and the travel (m) where following stops.
  struct Following {
    NodeId old = -1, current = -1;
    double until_m = 0.0;
  };
  std::optional<Following> following_;
  /// The last local search's covariance projection (loops.max_position_sigma_m), which the
  /// global search of the same observation uses.
  std::map<NodeId, ProjectedNode> projected_;
  CliqueGroupCache groups_;  ///< the projection's clique-group covariances, between calls
  HypothesisHook hook_;
};

}  // namespace lifelong::slam
