// What one loop search of one observation did, from its candidates to its decision
// (slam/loops/loop_closer.hpp). The mapper reports them in StepStats.
#pragma once

#include <limits>
#include <optional>

#include "slam/loops/loop_verifier.hpp"

namespace lifelong::slam {

/// What one submap match measured, whether it passed or not; NaN when no match ran (too few
/// reference points) or when it stopped at loops.min_score without a pose there
/// (loops.measure_low_scores false, MatcherConfig::cut_below_min_score).
struct MatchMeasure {
  /// The points' mean likelihood on the reference at the best pose (scan_matcher.hpp).
  double score = std::numeric_limits<double>::quiet_NaN();
  /// The best distinct rival's score over the best's (MatchResult::ambiguity; 0: no rival),
  /// which loops.max_ambiguity bounds.
  double ambiguity = std::numeric_limits<double>::quiet_NaN();
};

struct LoopAttempt {
  /// kFollow: matched where a pending closure by place puts the robot (loop_closer_follow.cpp).
  enum class Search { kLocal, kGlobal, kFollow };
  Search search = Search::kLocal;
  NodeId current = -1;  ///< the node searched for
  /// The node the best match was against: the likeliest candidate (local) or the most similar
  /// place matched (global); -1 when no match ran.
  NodeId old = -1;
  /// The best match's figures (of `old`'s submap), whether it passed or not.
  MatchMeasure measured;
  int candidates = 0;                   ///< nodes (local) or places (global) matched against
  double window_m = 0.0;                ///< the matcher's half-width...
  double window_rad = 0.0;              ///< ...and heading half-width
  std::optional<MatchRefusal> refused;  ///< why no hypothesis came of it
  bool proposed = false;                ///< a hypothesis went to the verifier
  int accepted = 0;  ///< closures the verifier accepted on it (its own or pending ones)
};

/// The search's name in loop_attempts.csv.
inline const char* SearchName(LoopAttempt::Search search) {
  switch (search) {
    case LoopAttempt::Search::kGlobal:
      return "global";
    case LoopAttempt::Search::kFollow:
      return "follow";
    case LoopAttempt::Search::kLocal:
      break;
  }
  return "local";
}

}  // namespace lifelong::slam
