// The map as the world most likely stands now (issue #35), for a pruned map whose scans have
// beams cut as outdated (the DPG removal policy, BeamCut). A cut shows a place as last seen;
// a place not seen since may have changed again. Each cell is taken as a two-state Markov
// chain, as in the dynamic occupancy grids of Meyer-Delius, Beinhofer and Burgard (AAAI 2012)
// and Tipaldi, Meyer-Delius and Burgard (IJRR 2013): after its last observation its belief
// relaxes toward the chain's stationary occupancy,
//   p(c, t) = pi(c) + (p_last(c) - pi(c)) exp(-((t - t_seen(c)) / tau)^k).
// With k = 1 it is the prediction step of a Markov chain whose two transition rates sum to
// 1 / tau. With k > 1 the time a cell keeps its state is Weibull-distributed (a semi-Markov
// chain): a place just seen to change is unlikely to change again at once, and one unseen
// for long has likely changed. (Biber and Duckett 2009 keep whole maps at several timescales
// instead.) Here
//   p_last(c): the cell as the map shows it, hits / (hits + misses);
//   pi(c):     its long-run occupancy, the same ratio over every scan that observed it as it
//              was taken: the map's counts plus what removals and cuts archived (CellLedger);
//   t_seen(c): the stamp of the latest scan that observed it (CellLedger).
// Only a cell a cut changed (the map saw it change) relaxes; every other is taken as static.
// A map without cuts (the standard mode, the information-gain policy) is its own present.
#pragma once

#include <functional>

#include "slam/grid/cell_ledger.hpp"
#include "slam/grid/grid_map.hpp"

namespace lifelong::slam {

/// tau and k above.
struct PresentTimescale {
  double tau_s = 0.0;  ///< <= 0: every cell shows p_last
  double shape = 1.0;  ///< k >= 1
};

/// Calls f(cell, p) for every cell `map` knows, with p(c, now_s) above. No ledger, or
/// tau_s <= 0: p = p_last.
void ForEachPresentCell(const GridMap& map, const CellLedger* ledger, double now_s,
                        const PresentTimescale& timescale,
                        const std::function<void(CellIndex, double)>& f);

}  // namespace lifelong::slam
