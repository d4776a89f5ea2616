// Following a closure by place (loops.global.follow_m). A closure the global search proposes
// waits in the group verifier (loop_verifier.hpp) until others confirm it. The others come
// from later searches by place, one every loops.global.every observations; where the robot
// only crosses an old place (a junction driven across, a doorway passed) the descriptors get
// one or two looks at it, and the next search finds the robot elsewhere. If the proposal is
// right, the old scans match the new ones where it puts the robot: at its closure composed
// with the odometry chain since. So at each observation until the proposal is confirmed,
// dropped or follow_m of travel old, the scan is matched there, against the old node nearest
// that pose, in a window of 3 sigma of the proposal's and the chain's uncertainty (the chain's
// variance as the verifier models it). The match passes the same tests as a search by place's,
// and goes through the same verifier. A wrong proposal would be followed into the wrong place,
// and in a row of identical aisles its follow-ups match there as well as the truth would: so
// only a proposal without a look-alike rival (loops.context_ambiguity) is followed
// (MatchPlaces).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "slam/graph/se2.hpp"
#include "slam/loops/loop_closer.hpp"

namespace lifelong::slam {
namespace {

// The old node nearest `at` (position) among those the robot has left (min_path_separation_m
// of travel), and its distance; id -1 when there is none.
struct NearestNode {
  NodeId id = -1;
  double distance_m = std::numeric_limits<double>::infinity();
};
NearestNode NearestOld(const LoopClosingView& view, NodeId current, const Pose2& at,
                       const LoopClosingConfig& lc) {
  const double left_m = view.nodes.at(current).travelled_m - lc.min_path_separation_m;
  NearestNode nearest;
  for (const auto& [id, node] : view.nodes) {
    if (node.travelled_m > left_m) continue;
    const Pose2& X = view.values.at(id);
    const double d = std::hypot(X.x - at.x, X.y - at.y);
    if (d < nearest.distance_m) nearest = {id, d};
  }
  return nearest;
}

}  // namespace

void LoopCloser::StartFollowing(const LoopClosingView& view, NodeId old, NodeId current) {
  const GlobalLoopConfig& g = config_.global;
  if (g.follow_m <= 0.0 || verifier_.FindPending(old, current) == nullptr) return;
  const double until_m =
      following_ ? following_->until_m : view.nodes.at(current).travelled_m + g.follow_m;
  following_ = Following{old, current, until_m};
}

std::optional<LoopAttempt> LoopCloser::Follow(const LoopClosingView& view, NodeId current,
                                              std::vector<LoopHypothesis>* accepted) {
  const LoopClosingConfig& lc = config_;
  const LoopHypothesis* h = verifier_.FindPending(following_->old, following_->current);
  const NodeData& cur = view.nodes.at(current);
  if (h == nullptr || cur.travelled_m > following_->until_m) {
    following_.reset();
    return std::nullopt;
  }
  const Pose2& X_c = view.values.at(h->current);
  const Pose2 guess =
      view.values.at(h->old) * h->T_old_current * Between(X_c, view.values.at(current));
  const NearestNode old = NearestOld(view, current, guess, lc);
  if (old.id < 0 || old.distance_m > lc.global.near_range_m) return std::nullopt;
  verifier_.NoteFollowAttempt();
  LoopAttempt attempt;
  attempt.search = LoopAttempt::Search::kFollow;
  attempt.current = current;
  attempt.candidates = 1;
  // The proposal's own uncertainty plus the chain's since (LoopVerifierConfig's model).
  const LoopVerifierConfig& v = lc.verify;
  const double chain_m = std::max(cur.travelled_m - h->travelled_m, 0.0);
  const double var_xy = std::max(h->covariance(0, 0), h->covariance(1, 1)) + v.base_var_xy_m2 +
                        v.var_xy_per_m * chain_m;
  const double var_th = h->covariance(2, 2) + v.base_var_rad2 + v.var_rad_per_m * chain_m;
  MatcherConfig mc = lc.matcher;
  mc.linear_window_m = attempt.window_m = Clamp3Sigma(var_xy, lc.min_window_m, lc.max_window_m);
  mc.angular_window_rad = attempt.window_rad =
      Clamp3Sigma(var_th, lc.min_window_rad, lc.max_window_rad);
  MatchRefusal why = MatchRefusal::kLowScore;
  const std::vector<Eigen::Vector2d> near = NearReturns(cur.points, lc.global);
  const std::vector<PlaceCandidate> matched =
      MatchCandidates(view, current, near.empty() ? nullptr : &near, {{old.id, {}, 0.0, guess, {}}},
                      mc, &why, &attempt);
  if (matched.empty()) {
    verifier_.NoteRefused(why);
    attempt.refused = why;
    return attempt;
  }
  const MatchResult& match = matched.front().match;
  // The closure goes to the old node nearest where the match puts the robot.
  const NodeId to = NearestOld(view, current, match.T_ref_cur, lc).id;
  verifier_.NoteFollowProposed();
  attempt.old = to;
  attempt.measured = {match.score, match.ambiguity};
  attempt.proposed = true;
  attempt.accepted = Propose(view, to, current, match, accepted);
  StartFollowing(view, to, current);
  return attempt;
}

}  // namespace lifelong::slam
