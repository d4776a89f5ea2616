#include "slam/grid/present_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lifelong::slam {
namespace {

double Occupancy(double hits, double misses) { return hits / (hits + misses); }

}  // namespace

void ForEachPresentCell(const GridMap& map, const CellLedger* ledger, double now_s,
                        const PresentTimescale& timescale,
                        const std::function<void(CellIndex, double)>& f) {
  map.ForEachKnownCell([&](CellIndex c, CellCounts shown) {
    if (!Touches(shown)) return;
    const double p_last = Occupancy(shown.hits, shown.misses);
    const CellLedger::Entry* e = ledger && timescale.tau_s > 0.0 ? ledger->Find(c) : nullptr;
    if (!e || !e->changed) {
      f(c, p_last);
      return;
    }
    // A count may go below 0 where a scan archived at one pose is rendered at another now.
    const double hits = std::max<std::int64_t>(0, std::int64_t{shown.hits} + e->hits);
    const double misses = std::max<std::int64_t>(0, std::int64_t{shown.misses} + e->misses);
    if (hits + misses <= 0.0) {
      f(c, p_last);
      return;
    }
    const double pi = Occupancy(hits, misses);
    const double since_s = std::max(0.0, now_s - ledger->SeenStamp(*e));  // never: infinite
    f(c, pi + (p_last - pi) * std::exp(-std::pow(since_s / timescale.tau_s, timescale.shape)));
  });
}

}  // namespace lifelong::slam
