// The world's state at a time, the surfaces gone by the end, and the stale share of a map.
#include "eval/truth/world_state.hpp"

#include <algorithm>

#include <gtest/gtest.h>

#include "eval/metrics/map_quality.hpp"

namespace lifelong::eval {
namespace {

// One wall, a door closed over [10, 20) s, and a box that moves at 30 s.
sim::World ChangingWorld() {
  sim::World w;
  sim::Wall wall;
  wall.points = {{0.0, 0.0}, {10.0, 0.0}};
  w.walls.push_back(wall);
  sim::Door door;
  door.name = "d";
  door.segment = {0.0, 4.0, 2.0, 4.0};
  door.closed_intervals_s = {{10.0, 20.0}};
  w.doors.push_back(door);
  sim::Box box;
  box.name = "b";
  box.center = {5.0, 2.0};
  box.width_m = 1.0;
  box.height_m = 1.0;
  box.moves = {{30.0, {8.0, 2.0}, 0.0}};
  w.boxes.push_back(box);
  return w;
}

bool Has(const std::vector<Segment>& set, const Segment& s) {
  for (const Segment& x : set) {
    if (x.x0 == s.x0 && x.y0 == s.y0 && x.x1 == s.x1 && x.y1 == s.y1) return true;
  }
  return false;
}

double MinX(const std::vector<Segment>& set, std::size_t from) {
  double x = 1e9;
  for (std::size_t i = from; i < set.size(); ++i) x = std::min({x, set[i].x0, set[i].x1});
  return x;
}

TEST(WorldState, WallsAtTakeTheDoorsAndBoxesOfThatTime) {
  const sim::World w = ChangingWorld();
  const Segment door{0.0, 4.0, 2.0, 4.0};
  EXPECT_FALSE(Has(WallsAt(w, 5.0), door));
  EXPECT_TRUE(Has(WallsAt(w, 15.0), door));
  EXPECT_FALSE(Has(WallsAt(w, 20.0), door));  // [begin, end)
  // The wall's one segment, then the box's four: at 4.5..5.5 before 30 s, 7.5..8.5 after.
  EXPECT_DOUBLE_EQ(MinX(WallsAt(w, 29.0), 1), 4.5);
  EXPECT_DOUBLE_EQ(MinX(WallsAt(w, 30.0), 1), 7.5);
}

TEST(WorldState, GoneSurfacesAreThoseThatStoodAndStandNoMore) {
  const sim::World w = ChangingWorld();
  EXPECT_TRUE(GoneSurfaces(w, 5.0).empty());   // nothing changed yet
  EXPECT_TRUE(GoneSurfaces(w, 15.0).empty());  // the door is closed now: present
  const std::vector<Segment> at25 = GoneSurfaces(w, 25.0);
  ASSERT_EQ(at25.size(), 1u);  // the door, open again
  const std::vector<Segment> at40 = GoneSurfaces(w, 40.0);
  ASSERT_EQ(at40.size(), 5u);  // the door and the box's first pose
  EXPECT_DOUBLE_EQ(MinX(at40, 1), 4.5);
  const GroundTruth truth = TruthOf(w, 40.0);
  EXPECT_EQ(truth.gone.size(), 5u);
  EXPECT_EQ(truth.walls.size(), 1u + 1u + 8u);  // every pose the box took
  EXPECT_EQ(truth.walls_now.size(), 1u + 4u);
}

TEST(StaleShare, CountsTheCellsThatShowWhatIsGone) {
  // A map with the wall and the box at its old pose: the box's cells are stale.
  const sim::World w = ChangingWorld();
  std::vector<Segment> old_map = WallsAt(w, 0.0);
  const OccupancyGrid map = RasterizeWalls(old_map, 0.05);
  const GroundTruth truth = TruthOf(w, 40.0);
  const double stale = StaleShare(map, truth.gone, truth.walls_now, Pose2());
  // The box's outline is 4 m of the 14 m drawn (the 10 m wall stands): about 4/14.
  EXPECT_GT(stale, 0.2);
  EXPECT_LT(stale, 0.35);
  // The present map holds nothing stale; nor does any map when nothing is gone.
  const OccupancyGrid now = RasterizeWalls(truth.walls_now, 0.05);
  EXPECT_DOUBLE_EQ(StaleShare(now, truth.gone, truth.walls_now, Pose2()), 0.0);
  EXPECT_DOUBLE_EQ(StaleShare(map, {}, truth.walls_now, Pose2()), 0.0);
}

}  // namespace
}  // namespace lifelong::eval
