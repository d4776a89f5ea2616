// The map as the world most likely stands now (slam/grid/present_view.hpp, cell_ledger.hpp):
// a cell a cut changed relaxes from what it shows toward its long-run occupancy over every
// scan that observed it, removed ones included; no other cell moves.
#include "slam/grid/present_view.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace lifelong::slam {
namespace {

/// One beam along +x from the origin.
LaserScan OneBeam(float range_m) {
  LaserScan s;
  s.angle_increment_rad = 0.01;
  s.range_max_m = 30.0;
  s.ranges_m = {range_m};
  return s;
}

// A wall at 4 m seen at 10 s and 20 s; at 100 s a box stands at 2 m. The first scan's beam is
// cut across the box (an object now stands there, what lay beyond still does: BeamCut with
// resume_m), and the second scan is removed, as the DPG rule would do.
class PresentView : public ::testing::Test {
 protected:
  PresentView() {
    const std::vector<CellUpdate> wall = map.TouchedCells(OneBeam(4.0f), Pose2());
    const std::vector<CellUpdate> box = map.TouchedCells(OneBeam(2.0f), Pose2());
    const std::vector<CellUpdate> cut =
        map.TouchedCells(OneBeam(4.0f), Pose2(), {BeamCut{0, 1.9f, 2.1f}});
    map.Add(wall);
    ledger.Observe(wall, 10.0);
    map.Add(wall);
    ledger.Observe(wall, 20.0);
    map.Add(box);
    ledger.Observe(box, 100.0);
    map.Move(wall, cut);  // the first scan, cut
    ledger.Recut(wall, cut);
    map.Remove(wall);  // the second scan, removed
    ledger.Archive(wall);
  }
  std::map<std::pair<int, int>, double> At(double now_s, double timescale_s,
                                           const CellLedger* with) const {
    std::map<std::pair<int, int>, double> p;
    ForEachPresentCell(map, with, now_s, {timescale_s, shape}, [&](CellIndex c, double occ) {
      p[{c.x, c.y}] = occ;
    });
    return p;
  }
  double At(double now_s, double timescale_s, double x_m) const {
    const CellIndex c = map.CellOf(x_m, 0.0);
    return At(now_s, timescale_s, &ledger).at({c.x, c.y});
  }
  GridMap map;
  CellLedger ledger;
  double shape = 1.0;
};

TEST_F(PresentView, ACutCellRelaxesTowardItsOccupancyOverEveryScan) {
  // The box's cell shows the box (1 hit: the first scan's miss cut, the second's removed);
  // over the three scans it had 1 hit and 2 misses: pi = 1/3. Last seen at 100 s.
  const double tau = 600.0, pi = 1.0 / 3.0;
  EXPECT_DOUBLE_EQ(At(100.0, tau, 2.02), 1.0);
  EXPECT_NEAR(At(100.0 + tau, tau, 2.02), pi + (1.0 - pi) * std::exp(-1.0), 1e-12);
  EXPECT_NEAR(At(100.0 + 50 * tau, tau, 2.02), pi, 1e-12);
}

TEST_F(PresentView, AboveShapeOneAFreshChangeHoldsLongerAndAnOldOneFadesFaster) {
  const double tau = 600.0, pi = 1.0 / 3.0;
  shape = 2.0;  // exp(-(dt / tau)^2)
  EXPECT_NEAR(At(100.0 + tau / 4, tau, 2.02), pi + (1.0 - pi) * std::exp(-1.0 / 16), 1e-12);
  EXPECT_NEAR(At(100.0 + tau, tau, 2.02), pi + (1.0 - pi) * std::exp(-1.0), 1e-12);
  EXPECT_NEAR(At(100.0 + 3 * tau, tau, 2.02), pi + (1.0 - pi) * std::exp(-9.0), 1e-12);
}

TEST_F(PresentView, CellsNoCutChangedShowWhatTheyShow) {
  EXPECT_DOUBLE_EQ(At(1e6, 600.0, 1.0), 0.0);   // free in every scan
  EXPECT_DOUBLE_EQ(At(1e6, 600.0, 4.02), 1.0);  // the wall beyond the box: resumed
  // The map's cells, no more: those only the removed scan saw are not shown.
  EXPECT_EQ(At(1e6, 600.0, &ledger).size(), At(1e6, 0.0, &ledger).size());
}

TEST_F(PresentView, WithoutATimescaleOrALedgerTheMapIsItsOwnPresent) {
  for (const auto& p : {At(1e6, 0.0, &ledger), At(1e6, 600.0, nullptr)}) {
    map.ForEachKnownCell([&](CellIndex c, CellCounts k) {
      EXPECT_DOUBLE_EQ(p.at({c.x, c.y}), static_cast<double>(k.hits) / (k.hits + k.misses));
    });
  }
}

TEST(CellLedger, RecutArchivesOnlyWhatTheCutTookOut) {
  GridMap map;
  CellLedger ledger;
  const std::vector<CellUpdate> whole = map.TouchedCells(OneBeam(4.0f), Pose2());
  ledger.Recut(whole, map.TouchedCells(OneBeam(4.0f), Pose2(), {BeamCut{0, 1.9f, 2.1f}}));
  const CellLedger::Entry* before = ledger.Find(map.CellOf(1.0, 0.0));  // short of the cut
  EXPECT_TRUE(before == nullptr || (!before->changed && before->misses == 0));
  const CellLedger::Entry* cut = ledger.Find(map.CellOf(2.02, 0.0));
  ASSERT_NE(cut, nullptr);
  EXPECT_TRUE(cut->changed);
  EXPECT_EQ(cut->misses, 1);
  EXPECT_EQ(ledger.SeenStamp(*cut), -std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace lifelong::slam
