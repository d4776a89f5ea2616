// change_recall: whether a map shows a door as it stands at the end, and when it was seen.
#include "eval/metrics/change_recall.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "eval/figures/change_tiles.hpp"
#include "eval/metrics/map_quality.hpp"

namespace lifelong::eval {
namespace {

// A wall along y = 0 with a 1 m doorway at x in [4, 5]; its door is closed over [0, 10) s.
sim::World DoorWorld() {
  sim::World w;
  sim::Wall a, b;
  a.points = {{0.0, 0.0}, {4.0, 0.0}};
  b.points = {{5.0, 0.0}, {9.0, 0.0}};
  w.walls = {a, b};
  sim::Door d;
  d.name = "d";
  d.segment = {4.0, 0.0, 5.0, 0.0};
  d.closed_intervals_s = {{0.0, 10.0}};
  w.doors.push_back(d);
  return w;
}

// One scan at t_s from (4.5, 2) looking down (-y) through the doorway, beams +-10 deg.
Observation LookThrough(double t_s) {
  Observation o;
  o.stamp_s = t_s;
  o.T_world_robot_true = Pose2(4.5, 2.0, -M_PI / 2.0);
  o.scan.angle_min_rad = -0.17;
  o.scan.angle_increment_rad = 0.017;
  o.scan.range_max_m = 30.0;
  o.scan.ranges_m.assign(21, 30.0f);  // no return: the room beyond is deep
  return o;
}

TEST(ChangeRecall, AnOpenDoorShownClosedIsNotThePresent) {
  const sim::World w = DoorWorld();
  const std::vector<Observation> stream{LookThrough(15.0)};
  const std::vector<Segment> walls{{0, 0, 4, 0}, {5, 0, 9, 0}}, door{{4, 0, 5, 0}};
  std::vector<Segment> with_door = walls;
  with_door.push_back(door[0]);
  const auto stale = ComputeChangeRecall(w, 20.0, stream, RasterizeWalls(with_door, 0.05), Pose2());
  ASSERT_TRUE(stale.has_value());
  ASSERT_EQ(stale->objects.count("door d"), 1u);
  EXPECT_FALSE(stale->objects.at("door d").shows_present);
  ASSERT_TRUE(stale->objects.at("door d").since_seen_s.has_value());
  EXPECT_NEAR(*stale->objects.at("door d").since_seen_s, 5.0, 1e-9);
  EXPECT_EQ(stale->recent, 1);
  EXPECT_DOUBLE_EQ(*stale->recall, 0.0);

  const auto current = ComputeChangeRecall(w, 20.0, stream, RasterizeWalls(walls, 0.05), Pose2());
  ASSERT_TRUE(current.has_value());
  EXPECT_TRUE(current->objects.at("door d").shows_present);
  EXPECT_DOUBLE_EQ(*current->recall, 1.0);

  // Before the door opened nothing changed; a door never seen counts in no recall.
  EXPECT_FALSE(ComputeChangeRecall(w, 5.0, stream, RasterizeWalls(walls, 0.05), Pose2()));
  const auto unseen = ComputeChangeRecall(w, 20.0, {}, RasterizeWalls(walls, 0.05), Pose2());
  ASSERT_TRUE(unseen.has_value());
  EXPECT_FALSE(unseen->recall.has_value());
  EXPECT_FALSE(unseen->objects.at("door d").since_seen_s.has_value());
}

// The report's strip: the door that opened, as a map that still shows it closed draws it:
// black cells under the red past outline; its caption says it is not shown as it stands.
TEST(ChangeTiles, DrawEachChangedObjectOverTheMap) {
  const sim::World w = DoorWorld();
  const std::vector<Segment> walls{{0, 0, 4, 0}, {5, 0, 9, 0}, {4, 0, 5, 0}};
  const OccupancyGrid stale = RasterizeWalls(walls, 0.05);
  const auto change = ComputeChangeRecall(w, 20.0, {LookThrough(15.0)}, stale, Pose2());
  ASSERT_TRUE(change.has_value());
  ASSERT_EQ(change->objects.at("door d").past.size(), 1u);  // open at the end: the door is past
  EXPECT_TRUE(change->objects.at("door d").present.empty());
  const std::string path = ::testing::TempDir() + "/change_tiles.png";
  std::remove(path.c_str());
  const std::string caption = WriteChangeTiles(path, *change, stale, Pose2());
  EXPECT_EQ(caption, "door d: not shown as it stands, seen 5 s before the end");
  std::ifstream png(path, std::ios::binary);
  ASSERT_TRUE(png.good());
  char magic[4] = {};
  png.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  // Nothing changed: no strip.
  ChangeRecall none;
  EXPECT_EQ(WriteChangeTiles(path + ".none", none, stale, Pose2()), "");
}

}  // namespace
}  // namespace lifelong::eval
