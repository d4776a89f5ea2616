// Group verification of loop closures (issue #16), after pairwise consistency maximization
// (Mangelson et al., ICRA 2018) and Olson's single-cluster test (2009), online: a closure
// is a *hypothesis* until enough others confirm it through the odometry between them.
//
// Two closures a = (i -> j, Z_a) and b = (k -> l, Z_b), with i, k old nodes and j, l
// current ones, close a cycle with the estimate's relative poses between j and l (recent
// incremental odometry) and between k and i (the map already built):
//
//   e_ab = t2v( Z_a * T_j_l * Z_b^-1 * T_k_i ),   T_x_y = X_x^-1 X_y at the current estimate,
//
// which is zero for two correct closures up to their noise and the drift of the two
// chains. They are *consistent* when e^T S^-1 e <= consistency_chi2, where S propagates
// the two closures' covariances and the two chains' drift through the SE(2) adjoints of the
// cycle (first order). A chain d metres long drifts by base + var_xy_per_m d in
// translation and base + var_rad_per_m d in heading, plus the lateral error the heading
// walk builds up, var_rad_per_m d^3 / 3; the current-side chain's length is the path
// travelled between j and l, the old side's the distance between k and i. A wrong
// closure into a look-alike place (the neighbouring aisle) is off by that place's offset and fails
// the test against correct ones, while a run of wrong closures along one aliased traversal is
// consistent among itself: that is why recently accepted closures count as evidence too.
//
// Rule, for each new hypothesis h:
//  1. If recently accepted closures (current node within window_m of travel before h's)
//     exist, and h is consistent with none of them while conflicting with at least one, h is
//     rejected: the map there is already anchored elsewhere.
//  2. Otherwise h joins the pending pool, and the largest mutually consistent set (greedy
//     maximum clique) among h, the pending hypotheses and the recent accepted closures that
//     contains h is found. When it holds at least min_group members, its pending members
//     are accepted together.
//  3. Pending hypotheses older than expiry_m of travel are dropped unconfirmed.
// Pending hypotheses never enter the graph, so no optimization or marginalization ever sees
// an unverified closure.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam {

struct LoopVerifierConfig {
  bool enabled = true;              ///< false: every hypothesis is accepted at once
  int min_group = 3;                ///< mutually consistent closures needed (h included)
  double consistency_chi2 = 11.34;  ///< 99 % gate, 3 dof, of the cycle error
  double window_m = 40.0;           ///< m of travel: accepted closures that count as evidence
  double expiry_m = 40.0;           ///< m of travel: a pending hypothesis waits this long
  double base_var_xy_m2 = 0.0025;   ///< m^2, chain variance at zero length (0.05 m)
  double var_xy_per_m = 0.0005;     ///< m^2 per m of chain (0.14 m after 40 m)
  double base_var_rad2 = 3e-4;      ///< rad^2 (1 deg)
  double var_rad_per_m = 3e-5;      ///< rad^2 per m of chain (2 deg after 40 m)
};

struct LoopHypothesis {
  NodeId old = 0;
  NodeId current = 0;
  Pose2 T_old_current;          ///< measured
  Eigen::Matrix3d information;  ///< of the edge error (right perturbation of T_old_current)
  Eigen::Matrix3d covariance;   ///< its inverse
  double travelled_m = 0.0;     ///< robot path length at `current`
  bool injected = false;        ///< a deliberately wrong closure (false-closure test)
};

/// Counts over the run; summary.json's loop_verification.
struct LoopVerifierStats {
  int proposed = 0;  ///< hypotheses from the matcher
  int accepted = 0;
  int rejected = 0;    ///< conflicting with the accepted closures around them
  int expired = 0;     ///< never confirmed
  int not_unique = 0;  ///< matches refused before verification: not locally unique
  int injected = 0;    ///< wrong closures injected (false-closure test)
  int injected_accepted = 0;
  // The funnel before verification: attempts = few_points + low_score + ambiguous +
  // not_unique + approach_disagrees + implausible + proposed.
  int attempts = 0;     ///< observations with a candidate inside the gate
  int few_points = 0;   ///< ...whose submap had fewer points in reach than the minimum
  int low_score = 0;    ///< ...whose best match scored below the minimum
  int ambiguous = 0;    ///< ...whose best match had a close second farther away
  int implausible = 0;  ///< ...whose correction lay outside the consistency gate
  /// ...whose rival the robot's approach fitted better (loops.context_ambiguity)
  int approach_disagrees = 0;
  /// Observations with no attempt whose only candidates inside the gate were uncertain
  /// beyond the largest window, between the searches of loops.beyond_window_every.
  int beyond_window = 0;
  /// Of the attempts, those of the global search (loops.global), and of its proposals.
  int global_attempts = 0;
  int global_proposed = 0;
  /// Searches by place that ran (the place dense enough to describe), with a candidate
  /// within loops.global.max_distance or not: global_searches - global_attempts found none.
  int global_searches = 0;
  /// Of the attempts, the matches where a pending closure by place puts the robot
  /// (loops.global.follow_m), and of their proposals.
  int follow_attempts = 0;
  int follow_proposed = 0;
};

/// Why the mapper refused a loop-closure match before it became a hypothesis.
enum class MatchRefusal {
  kFewPoints,
  kLowScore,
  kAmbiguous,
  kNotUnique,
  kImplausible,
  kApproachDisagrees
};

/// A refusal's name, as summary.json's loop_verification and loop_attempts.csv give it.
inline const char* MatchRefusalName(MatchRefusal why) {
  switch (why) {
    case MatchRefusal::kFewPoints:
      return "few_points";
    case MatchRefusal::kLowScore:
      return "low_score";
    case MatchRefusal::kAmbiguous:
      return "ambiguous";
    case MatchRefusal::kNotUnique:
      return "not_unique";
    case MatchRefusal::kImplausible:
      return "implausible";
    case MatchRefusal::kApproachDisagrees:
      return "approach_disagrees";
  }
  return "unknown";
}

class LoopVerifier {
 public:
  explicit LoopVerifier(const LoopVerifierConfig& config) : config_(config) {}

  /// Considers `h`; returns the hypotheses accepted now (h and pending ones it confirms),
  /// in the order they were proposed. `values` is the current estimate.
  std::vector<LoopHypothesis> Add(const LoopHypothesis& h, const Values& values);
  /// Drops pending hypotheses older than expiry_m before `travelled_m`.
  void Expire(double travelled_m);
  /// Forgets accepted closures involving a removed node (they no longer count as evidence).
  void ForgetNode(NodeId id);
  /// Counts a loop-closing attempt (a candidate inside the gate).
  void NoteAttempt() { ++stats_.attempts; }
  void NoteGlobalAttempt() {
    ++stats_.attempts;
    ++stats_.global_attempts;
  }
  void NoteGlobalProposed() { ++stats_.global_proposed; }
  void NoteGlobalSearch() { ++stats_.global_searches; }
  void NoteFollowAttempt() {
    ++stats_.attempts;
    ++stats_.follow_attempts;
  }
  void NoteFollowProposed() { ++stats_.follow_proposed; }
  void NoteBeyondWindow() { ++stats_.beyond_window; }
  /// Counts an attempt the mapper refused before it became a hypothesis.
  void NoteRefused(MatchRefusal why) {
    // In the order of MatchRefusal.
    static constexpr int LoopVerifierStats::*kCount[] = {
        &LoopVerifierStats::few_points,  &LoopVerifierStats::low_score,
        &LoopVerifierStats::ambiguous,   &LoopVerifierStats::not_unique,
        &LoopVerifierStats::implausible, &LoopVerifierStats::approach_disagrees};
    ++(stats_.*kCount[static_cast<int>(why)]);
  }
  /// True when a pending hypothesis involves the node (pruning must keep it).
  bool IsPending(NodeId id) const;
  /// The pending hypothesis from `old` to `current`, if one waits.
  const LoopHypothesis* FindPending(NodeId old, NodeId current) const;

  /// Whether two closures are consistent at the current estimate (the header's test).
  bool Consistent(const LoopHypothesis& a, const LoopHypothesis& b, const Values& values) const;

  const std::vector<LoopHypothesis>& pending() const { return pending_; }
  const LoopVerifierStats& stats() const { return stats_; }

 private:
  void Accept(const LoopHypothesis& h, std::vector<LoopHypothesis>* out);

  LoopVerifierConfig config_;
  std::vector<LoopHypothesis> pending_;
  std::vector<LoopHypothesis> accepted_;  ///< within window_m of the newest, as evidence
  LoopVerifierStats stats_;
};

}  // namespace lifelong::slam
