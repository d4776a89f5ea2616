// change_recall: whether a map shows a door as it stands at the end, and when it was seen.
#include "eval/metrics/change_recall.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "eval/figures/change_tiles.hpp"
#include "eval/metrics/map_quality.hpp"
#include "eval/truth/truth_raster.hpp"
#include "eval/truth/world_state.hpp"

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

// A scan at t_s from (x, y) looking down (-y), its beams from angle_min by increment; a
// 30 m laser, its ranges left to the caller.
Observation LookingDown(double t_s, double x, double y, double angle_min, double increment) {
  Observation o;
  o.stamp_s = t_s;
  o.T_world_robot_true = Pose2(x, y, -M_PI / 2.0);
  o.scan.angle_min_rad = angle_min;
  o.scan.angle_increment_rad = increment;
  o.scan.range_max_m = 30.0;
  return o;
}

// One scan at t_s from (4.5, 2) looking down (-y) through the doorway, beams +-10 deg.
Observation LookThrough(double t_s) {
  Observation o = LookingDown(t_s, 4.5, 2.0, -0.17, 0.017);
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
  EXPECT_EQ(stale->objects.at("door d").shows_present, false);
  ASSERT_TRUE(stale->objects.at("door d").since_seen_s.has_value());
  EXPECT_NEAR(*stale->objects.at("door d").since_seen_s, 5.0, 1e-9);
  EXPECT_EQ(stale->recent, 1);
  EXPECT_DOUBLE_EQ(*stale->recall, 0.0);

  const auto current = ComputeChangeRecall(w, 20.0, stream, RasterizeWalls(walls, 0.05), Pose2());
  ASSERT_TRUE(current.has_value());
  EXPECT_EQ(current->objects.at("door d").shows_present, true);
  EXPECT_DOUBLE_EQ(*current->recall, 1.0);

  // Before the door opened nothing changed; a door never seen counts in no recall.
  EXPECT_FALSE(ComputeChangeRecall(w, 5.0, stream, RasterizeWalls(walls, 0.05), Pose2()));
  const auto unseen = ComputeChangeRecall(w, 20.0, {}, RasterizeWalls(walls, 0.05), Pose2());
  ASSERT_TRUE(unseen.has_value());
  EXPECT_FALSE(unseen->recall.has_value());
  EXPECT_FALSE(unseen->objects.at("door d").since_seen_s.has_value());
}

// stale_seen_cells counts a stale cell only where the robot saw the place empty after the
// change: the door shown closed, seen open through the doorway, is stale and seen; never
// looked at again, it is stale and not seen.
TEST(ChangeRecall, StaleCellsSeenGoneAreThoseABeamCrossed) {
  const sim::World w = DoorWorld();
  const std::vector<Segment> with_door{{0, 0, 4, 0}, {5, 0, 9, 0}, {4, 0, 5, 0}};
  const OccupancyGrid map = RasterizeWalls(with_door, 0.05);
  const TruthRaster raster(TruthOf(w, 20.0), {}, 0.05);
  const double stale = StaleShare(map, raster, Pose2());
  ASSERT_GT(stale, 0.0);
  Observation narrow = LookingDown(15.0, 4.5, 2.0, -0.05, 0.017);  // +-3 degrees: +-0.1 m
  narrow.scan.ranges_m.assign(7, 30.0f);
  const auto seen = ComputeChangeRecall(w, 20.0, {narrow}, map, Pose2(), SIZE_MAX, &raster);
  ASSERT_TRUE(seen.has_value() && seen->stale_seen.has_value());
  EXPECT_GT(*seen->stale_seen, 0.0);
  EXPECT_LT(*seen->stale_seen, 0.5 * stale);  // the door's middle only
  const auto wide =
      ComputeChangeRecall(w, 20.0, {LookThrough(15.0)}, map, Pose2(), SIZE_MAX, &raster);
  EXPECT_DOUBLE_EQ(*wide->stale_seen, stale);  // +-10 degrees: the whole door
  const auto unseen = ComputeChangeRecall(w, 20.0, {}, map, Pose2(), SIZE_MAX, &raster);
  ASSERT_TRUE(unseen.has_value() && unseen->stale_seen.has_value());
  EXPECT_DOUBLE_EQ(*unseen->stale_seen, 0.0);
  EXPECT_FALSE(ComputeChangeRecall(w, 20.0, {}, map, Pose2())->stale_seen.has_value());
}

// A sighting before the door's last change saw a state the world has left: a door seen
// closed at 8 s and opened at 10 s is not "seen" at the end, and counts in no recall.
TEST(ChangeRecall, ASightingBeforeTheLastChangeDoesNotCount) {
  const sim::World w = DoorWorld();
  Observation closed = LookThrough(8.0);
  closed.scan.ranges_m.assign(21, 2.0f);  // the closed door, 2 m below the laser
  const std::vector<Segment> walls{{0, 0, 4, 0}, {5, 0, 9, 0}};
  const auto before = ComputeChangeRecall(w, 20.0, {closed}, RasterizeWalls(walls, 0.05), Pose2());
  ASSERT_TRUE(before.has_value());
  EXPECT_FALSE(before->objects.at("door d").since_seen_s.has_value());
  EXPECT_EQ(before->recent, 0);
  EXPECT_FALSE(before->recall.has_value());
  // Seen again open after the change: that sighting counts.
  const auto after = ComputeChangeRecall(w, 20.0, {closed, LookThrough(15.0)},
                                         RasterizeWalls(walls, 0.05), Pose2());
  ASSERT_TRUE(after.has_value());
  EXPECT_NEAR(*after->objects.at("door d").since_seen_s, 5.0, 1e-9);
  EXPECT_EQ(after->recent, 1);
}

// A box 1 x 0.5 m that moved at 5 s from (2, 1) to (5, 1), seen at 10 s from (3.5, 4) looking
// down: the laser sees its new top and left faces, and crosses its old place. Ranges are
// cast against the present outline; a beam that hits nothing has no return.
sim::World MovedBoxWorld() {
  sim::World w;
  sim::Box b;
  b.name = "b";
  b.center = {2.0, 1.0};
  b.width_m = 1.0;
  b.height_m = 0.5;
  b.moves.push_back({5.0, {5.0, 1.0}, 0.0});
  w.boxes.push_back(b);
  return w;
}

Observation LookDownAt(const std::vector<Segment>& outline, double t_s) {
  Observation o = LookingDown(t_s, 3.5, 4.0, -1.2, 0.01);
  for (int i = 0; i <= 240; ++i) {
    const double a = -M_PI / 2.0 + o.scan.Bearing(static_cast<std::size_t>(i));
    double best = 30.0;
    for (const Segment& s : outline) {  // ray (3.5, 4) + t (cos a, sin a) against s
      const double ex = s.x1 - s.x0, ey = s.y1 - s.y0, c = std::cos(a), d = std::sin(a);
      const double den = c * ey - d * ex;
      if (std::abs(den) < 1e-12) continue;
      const double t = ((s.x0 - 3.5) * ey - (s.y0 - 4.0) * ex) / den;
      const double u = ((s.x0 - 3.5) * d - (s.y0 - 4.0) * c) / den;
      if (t > 0.0 && u >= 0.0 && u <= 1.0) best = std::min(best, t);
    }
    o.scan.ranges_m.push_back(static_cast<float>(best));
  }
  return o;
}

// Judged on what was seen: a map holding the faces the laser saw shows the box as it
// stands, though its far faces are in no map; a map still holding the place it left does
// not; and a scan from before the move sees nothing of its present.
TEST(ChangeRecall, AMovedBoxIsJudgedOnTheFacesSeen) {
  const sim::World w = MovedBoxWorld();
  const std::vector<Segment> now = BoxOutlineAt(w.boxes[0], 20.0);
  const std::vector<Segment> before = BoxOutlineAt(w.boxes[0], 0.0);
  const Observation scan = LookDownAt(now, 10.0);
  std::vector<Segment> seen_faces;  // the top face (y = 1.25): a third of the outline
  for (const Segment& s : now) {
    if (s.y0 == 1.25 && s.y1 == 1.25) seen_faces.push_back(s);
  }
  ASSERT_EQ(seen_faces.size(), 1u);
  const auto current =
      ComputeChangeRecall(w, 20.0, {scan}, RasterizeWalls(seen_faces, 0.05), Pose2());
  ASSERT_TRUE(current.has_value());
  EXPECT_EQ(current->objects.at("box b").shows_present, true);
  EXPECT_NEAR(*current->objects.at("box b").since_seen_s, 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(*current->recall, 1.0);

  std::vector<Segment> stale = seen_faces;
  stale.insert(stale.end(), before.begin(), before.end());
  const auto old = ComputeChangeRecall(w, 20.0, {scan}, RasterizeWalls(stale, 0.05), Pose2());
  EXPECT_EQ(old->objects.at("box b").shows_present, false);
  // Why: its new face is there, and so is its old place.
  EXPECT_GE(*old->objects.at("box b").present_shown, 0.5);
  EXPECT_GE(*old->objects.at("box b").past_shown, 0.5);
  const auto empty = ComputeChangeRecall(w, 20.0, {scan}, RasterizeWalls({}, 0.05), Pose2());
  EXPECT_EQ(empty->objects.at("box b").shows_present, false);
  EXPECT_DOUBLE_EQ(*empty->objects.at("box b").present_shown, 0.0);  // its new face missing

  const auto early = ComputeChangeRecall(w, 20.0, {LookDownAt(before, 4.0)},
                                         RasterizeWalls(seen_faces, 0.05), Pose2());
  EXPECT_FALSE(early->objects.at("box b").since_seen_s.has_value());
  EXPECT_FALSE(early->objects.at("box b").shows_present.has_value());  // no map could
  EXPECT_FALSE(early->recall.has_value());
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
