// The approach test of a loop-closure match (loops.context_ambiguity): a match whose rival
// scored close to it is kept only when the robot's way in agrees. One scan in an aisle sees
// the two shelves every aisle shows, so the aisle next door can score better than the right
// one; the scans that led there saw the cross aisle, or the door, that tells them apart.
// Those scans are placed by the estimate relative to the current node (the sequential
// matcher's chain over a few metres, good to centimetres) and scored at the match's pose and
// at the rival's against the scans of the nodes observed before them, with the match's own
// likelihood field (scan_matcher.hpp step 1). The search found the winner on one scan; this
// asks which of the two the last metres of travel fit.
#pragma once

#include "slam/loops/loop_closer.hpp"
#include "slam/loops/node_reach.hpp"

namespace lifelong::slam {

/// Whether the points of the nodes observed in the last lc.context_span_m of travel before
/// `current` (placed in current's frame by the estimate) score at `match` (current's pose)
/// at least as well as at `rival`, against the points of the nodes observed more than
/// lc.min_path_separation_m before that span. True when either side has too few points to
/// judge by. `reach` keeps the nodes' reaches between calls; `grid` is a scratch table,
/// rebuilt.
bool ApproachAgrees(const LoopClosingView& view, NodeId current, const Pose2& match,
                    const Pose2& rival, const LoopClosingConfig& lc, NodeReach* reach,
                    ReferenceGrid* grid);

}  // namespace lifelong::slam
