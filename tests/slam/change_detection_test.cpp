// Scan-to-scan change detection (slam/grid/change_detection.hpp) on hand-made worlds with an exact
// ray caster: a door that opens, a box that appears, a static room, and poses that disagree.
#include "slam/grid/change_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

using testing::AddRectangle;
using testing::SimulateScan;
using testing::World;

// A 10 m x 6 m room with a 0.1 m thick partition at x = 6 from y = 0 to y = 6 and a door in
// it (y in [2, 4]) that is `closed` or open.
World RoomWithDoor(bool closed) {
  World w;
  AddRectangle(0.0, 0.0, 10.0, 6.0, &w);
  w.push_back({6.0, 0.0, 6.0, 2.0});
  w.push_back({6.0, 4.0, 6.0, 6.0});
  if (closed) w.push_back({6.0, 2.0, 6.0, 4.0});
  return w;
}

const Pose2 kOld(2.0, 3.0, 0.0);
const Pose2 kNew(2.5, 2.8, 0.2);

TEST(ChangeDetection, AStaticPlaceShowsNoChange) {
  const World w = RoomWithDoor(true);
  const ScanComparison c =
      CompareScans(SimulateScan(w, kOld), kOld, SimulateScan(w, kNew), kNew, {});
  EXPECT_TRUE(c.compared);
  EXPECT_GT(c.agree, 200);
  EXPECT_EQ(c.disagree, 0);
  EXPECT_TRUE(c.outdated.empty());
  EXPECT_TRUE(c.news.empty());
}

// The door seen closed, then open: the older scan's returns on the door are seen through.
TEST(ChangeDetection, AnOpenedDoorOutdatesTheReturnsOnIt) {
  const LaserScan older = SimulateScan(RoomWithDoor(true), kOld);
  const LaserScan newer = SimulateScan(RoomWithDoor(false), kNew);
  const ScanComparison c = CompareScans(older, kOld, newer, kNew, {});
  ASSERT_TRUE(c.compared);
  ASSERT_GE(c.outdated.size(), 20u);  // the 2 m door spans 28 of the 1-degree beams at 4 m
  for (const BeamCut& cut : c.outdated) {
    const std::uint32_t b = cut.beam;
    EXPECT_EQ(cut.free_to_m, older.ranges_m[b]);  // the space up to the door was free, and is
    const double a = kOld.theta + older.Bearing(b), r = older.ranges_m[b];
    const double x = kOld.x + r * std::cos(a), y = kOld.y + r * std::sin(a);
    EXPECT_NEAR(x, 6.0, 0.01) << "beam " << b;  // on the door, nowhere else
    EXPECT_GT(y, 1.9);
    EXPECT_LT(y, 4.1);
  }
  EXPECT_FALSE(c.news.empty());
}

// The door seen open, then closed: the older scan's beams through the doorway end beyond
// an object that is there now.
TEST(ChangeDetection, AClosedDoorOutdatesTheBeamsThatPassedIt) {
  const LaserScan older = SimulateScan(RoomWithDoor(false), kOld);
  const LaserScan newer = SimulateScan(RoomWithDoor(true), kNew);
  const ScanComparison c = CompareScans(older, kOld, newer, kNew, {});
  ASSERT_TRUE(c.compared);
  ASSERT_GE(c.outdated.size(), 20u);
  for (const BeamCut& cut : c.outdated) {
    const float r = older.ranges_m[cut.beam];
    EXPECT_GT(r, 7.0) << "beam " << cut.beam;
    // Free only up to short of the door now standing at x = 6, 3.5-4.3 m along these beams;
    // unknown for the margin on both sides of it and the door's unseen depth (1 m); then
    // the room behind, free when the beam crossed it, and the return on its far wall,
    // which still stands, traced again.
    EXPECT_GT(cut.free_to_m, 3.0f);
    EXPECT_LT(cut.free_to_m, 4.1f);
    EXPECT_GT(cut.resume_m, cut.free_to_m + 1.55f) << "beam " << cut.beam;
    EXPECT_LT(cut.resume_m, cut.free_to_m + 1.8f) << "beam " << cut.beam;
    EXPECT_LT(cut.resume_m, r - 0.3f) << "beam " << cut.beam;
  }
  // With no depth bound, the beam keeps its return alone.
  ChangeDetectionConfig whole;
  whole.added_depth_m = std::numeric_limits<double>::infinity();
  const ScanComparison w = CompareScans(older, kOld, newer, kNew, whole);
  ASSERT_EQ(w.outdated.size(), c.outdated.size());
  for (const BeamCut& cut : w.outdated)
    EXPECT_NEAR(cut.resume_m, older.ranges_m[cut.beam] - 0.3f, 1e-4f);
}

// A corridor (y in [0, 3]) with a 1 m door in its north wall at x in [12.5, 13.5] and a room
// behind it; the door `closed` or open.
World CorridorWithDoor(bool closed) {
  World w;
  AddRectangle(0.0, 0.0, 30.0, 3.0, &w);
  w.erase(
      std::remove_if(w.begin(), w.end(), [](const auto& s) { return s.y0 == 3.0 && s.y1 == 3.0; }),
      w.end());
  w.push_back({0.0, 3.0, 12.5, 3.0});
  w.push_back({13.5, 3.0, 30.0, 3.0});
  w.push_back({11.0, 3.0, 11.0, 7.0});
  w.push_back({11.0, 7.0, 15.0, 7.0});
  w.push_back({15.0, 7.0, 15.0, 3.0});
  if (closed) w.push_back({12.5, 3.0, 13.5, 3.0});
  return w;
}

// The door seen open from down the corridor, where only two or three beams pass the
// doorway, then closed from beside it: each of those beams is outdated, though its
// neighbours hit the wall and it forms no run of its own. Seen closed both times, with a
// 3 cm error of the poses, nothing is.
TEST(ChangeDetection, ABeamGrazingAClosedDoorwayFromAfarIsOutdated) {
  const Pose2 near(12.0, 1.2, 0.3);
  for (const Pose2& far : {Pose2(8.0, 1.5, 0.0), Pose2(6.0, 1.5, 0.0)}) {
    const LaserScan older = SimulateScan(CorridorWithDoor(false), far);
    const LaserScan newer = SimulateScan(CorridorWithDoor(true), near);
    std::vector<std::uint32_t> through;  // the older beams that crossed the doorway
    for (std::uint32_t b = 0; b < older.ranges_m.size(); ++b) {
      const double a = far.theta + older.Bearing(b);
      if (std::sin(a) <= 0.0) continue;
      const double t = (3.0 - far.y) / std::sin(a), x = far.x + t * std::cos(a);
      if (x > 12.5 && x < 13.5 && older.ranges_m[b] > t + 0.5) through.push_back(b);
    }
    ASSERT_GE(through.size(), 1u);
    ASSERT_LE(through.size(), 3u);
    const ScanComparison c = CompareScans(older, far, newer, near, {});
    ASSERT_TRUE(c.compared);
    std::vector<std::uint32_t> cut;
    for (const BeamCut& b : c.outdated) cut.push_back(b.beam);
    EXPECT_EQ(cut, through) << "from x = " << far.x;
    for (const BeamCut& b : c.outdated) EXPECT_LT(b.free_to_m, older.ranges_m[b.beam]);

    const LaserScan same = SimulateScan(CorridorWithDoor(true), far);
    const ScanComparison none = CompareScans(same, far * Pose2(0.03, -0.03, 0.0), newer, near, {});
    EXPECT_TRUE(none.outdated.empty()) << none.outdated.size();
  }
}

// Each of the older beams `through` is among c's outdated beams.
void ExpectCut(const ScanComparison& c, const std::vector<std::uint32_t>& through) {
  std::vector<std::uint32_t> cut;
  for (const BeamCut& b : c.outdated) cut.push_back(b.beam);
  for (const std::uint32_t b : through)
    EXPECT_TRUE(std::binary_search(cut.begin(), cut.end(), b)) << "beam " << b;
}

// The doorway seen open up close, where some thirty beams cross it, then the door closed
// from down the corridor, where six returns fall on it: every older beam through the door
// between them is outdated, not only the six nearest their bearings. Seen closed both
// times, with a 3 cm error of the poses, nothing is.
TEST(ChangeDetection, ADoorClosedSeenFromAfarOutdatesEveryBeamThatCrossedIt) {
  const Pose2 close(13.0, 1.5, 1.5707963267948966), far(9.0, 1.0, 0.3);
  const LaserScan older = SimulateScan(CorridorWithDoor(false), close);
  const LaserScan newer = SimulateScan(CorridorWithDoor(true), far);
  double x_lo = 99.0, x_hi = -99.0;  // the door's returns in the newer scan
  for (std::size_t b = 0; b < newer.ranges_m.size(); ++b) {
    const double a = far.theta + newer.Bearing(b), r = newer.ranges_m[b];
    const double x = far.x + r * std::cos(a), y = far.y + r * std::sin(a);
    if (std::abs(y - 3.0) < 1e-6 && x > 12.5 && x < 13.5)
      x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
  }
  ASSERT_GT(x_hi - x_lo, 0.5);
  std::vector<std::uint32_t> through;  // the older beams that crossed the door between them
  for (std::uint32_t b = 0; b < older.ranges_m.size(); ++b) {
    const double a = close.theta + older.Bearing(b);
    if (std::sin(a) <= 0.0) continue;
    const double x = close.x + (3.0 - close.y) / std::sin(a) * std::cos(a);
    if (x > x_lo + 0.02 && x < x_hi - 0.02) through.push_back(b);
  }
  ASSERT_GE(through.size(), 20u);
  const ScanComparison c = CompareScans(older, close, newer, far, {});
  ASSERT_TRUE(c.compared);
  ExpectCut(c, through);
  for (const BeamCut& b : c.outdated) {
    const double a = close.theta + older.Bearing(b.beam);
    const double to_door = (3.0 - close.y) / std::sin(a);
    EXPECT_NEAR(b.free_to_m, to_door - 0.3, 0.02) << "beam " << b.beam;  // short of the door
  }

  const LaserScan same = SimulateScan(CorridorWithDoor(true), close);
  const ScanComparison none = CompareScans(same, close * Pose2(0.03, -0.03, 0.0), newer, far, {});
  EXPECT_TRUE(none.outdated.empty()) << none.outdated.size();
}

// A box put down where the older scan's outermost beams passed: the robot faced south, and
// its first beams ran west along y = 3 to the far wall. Seen from the north-east, the box's
// east face lies mostly outside the older scan's field of view, so only two or three of the
// newer returns on it can be judged; the face runs on past that edge, and those returns
// still outdate the older beams through the box, the first beam too. Unchanged, nothing is.
TEST(ChangeDetection, ABoxAtTheEdgeOfTheOlderViewOutdatesTheBeamsThroughIt) {
  const auto room = [](bool box) {
    World w;
    AddRectangle(0.0, 0.0, 10.0, 6.0, &w);
    if (box) AddRectangle(3.0, 2.8, 3.8, 3.5, &w);
    return w;
  };
  const Pose2 older_pose(7.0, 3.0, -1.5707963267948966), newer_pose(6.5, 5.0, -2.0);
  const LaserScan older = SimulateScan(room(false), older_pose);
  const LaserScan newer = SimulateScan(room(true), newer_pose);
  std::vector<std::uint32_t> through;  // older beams that cross the box's east face
  for (std::uint32_t b = 0; b < older.ranges_m.size(); ++b) {
    const double a = older_pose.theta + older.Bearing(b);
    if (std::cos(a) >= 0.0) continue;
    const double y = older_pose.y + (3.8 - older_pose.x) * std::tan(a);
    if (y > 2.86 && y < 3.48) through.push_back(b);  // not within a return of the corner
  }
  ASSERT_EQ(through.size(), 3u);
  ASSERT_EQ(through.front(), 0u);
  const ScanComparison c = CompareScans(older, older_pose, newer, newer_pose, {});
  ASSERT_TRUE(c.compared);
  ExpectCut(c, through);
  for (const BeamCut& b : c.outdated) {
    const double to_face =
        (older_pose.x - 3.8) / std::abs(std::cos(older_pose.theta + older.Bearing(b.beam)));
    EXPECT_NEAR(b.free_to_m, to_face - 0.3, 0.05) << "beam " << b.beam;  // short of the face
  }
  const ScanComparison none =
      CompareScans(SimulateScan(room(true), older_pose), older_pose, newer, newer_pose, {});
  EXPECT_TRUE(none.outdated.empty()) << none.outdated.size();
}

// Scans of an unchanged room whose poses disagree by 0.4-0.8 m (drift before a loop
// closure) are not compared: their disagreement is the poses', not the world's. An error of
// 0.2 m or 0.06 rad, within the margin, finds no change either.
TEST(ChangeDetection, ScansWhosePosesDisagreeAreNotCompared) {
  World w = RoomWithDoor(true);
  AddRectangle(3.0, 4.5, 3.6, 5.2, &w);
  AddRectangle(8.0, 1.0, 8.5, 1.4, &w);
  const LaserScan older = SimulateScan(w, kOld), newer = SimulateScan(w, kNew);
  for (const Pose2& e :
       {Pose2(0.0, 0.5, 0.0), Pose2(0.5, 0.0, 0.0), Pose2(0.8, 0.0, 0.0), Pose2(0.3, 0.3, 0.1)}) {
    const ScanComparison c = CompareScans(older, kOld, newer, kNew * e, {});
    EXPECT_FALSE(c.compared) << e.x << " " << e.y << " " << e.theta;
    EXPECT_TRUE(c.outdated.empty());
  }
  for (const Pose2& e : {Pose2(0.2, 0.0, 0.0), Pose2(0.0, 0.0, 0.06)}) {
    const ScanComparison c = CompareScans(older, kOld, newer, kNew * e, {});
    EXPECT_TRUE(c.compared);
    EXPECT_TRUE(c.outdated.empty()) << c.outdated.size();
  }
}

// A return at a corner, where one beam hits and its neighbour misses: no change.
TEST(ChangeDetection, AThinPostSeenFromElsewhereIsNoChange) {
  World w = RoomWithDoor(true);
  AddRectangle(4.0, 2.9, 4.05, 2.95, &w);  // a 5 cm post
  const ScanComparison c =
      CompareScans(SimulateScan(w, kOld), kOld, SimulateScan(w, kNew), kNew, {});
  EXPECT_TRUE(c.compared);
  EXPECT_TRUE(c.outdated.empty());
}

// A desk gone from the room's far side, seen from where a cabinet put down since hides much
// of what the older scan saw: the hidden returns are not seen by both scans, so they neither
// agree nor disagree, and the scans are compared on the rest (the desk's face is seen
// through). Counted among the judged, they kept the scans from being compared at all.
TEST(ChangeDetection, ReturnsHiddenBehindANearerObjectDoNotStopTheComparison) {
  World before, after;
  AddRectangle(0.0, 0.0, 10.0, 6.0, &before);
  after = before;
  AddRectangle(7.0, 1.0, 7.7, 2.4, &before);  // the desk, its face at x = 7
  AddRectangle(3.0, 3.1, 3.3, 6.0, &after);   // the cabinet, 0.5 m from the newer pose
  AddRectangle(3.0, 0.0, 3.3, 0.6, &after);
  const LaserScan older = SimulateScan(before, kOld), newer = SimulateScan(after, kNew);
  const ScanComparison c = CompareScans(older, kOld, newer, kNew, {});
  EXPECT_GT(c.hidden, 0);
  EXPECT_LT(c.agree, 0.6 * c.judged) << c.agree << " of " << c.judged;  // the old rule's test
  ASSERT_TRUE(c.compared) << c.agree << " of " << c.judged - c.hidden;
  int removed = 0;  // returns seen through (the cabinet's cuts resume past it)
  for (const BeamCut& cut : c.outdated) {
    if (cut.Resumes()) continue;
    ++removed;
    const double a = kOld.theta + older.Bearing(cut.beam), r = older.ranges_m[cut.beam];
    EXPECT_NEAR(kOld.x + r * std::cos(a), 7.0, 0.01) << "beam " << cut.beam;  // the desk's face
  }
  EXPECT_GE(removed, 4);
}

// A cabinet put down in the room by its door, glimpsed from down the corridor past the
// doorway's jamb, which leaves three beams on it: those returns form no run of four, yet a
// nearer surface (the jamb) ends the glimpse, so it needs only min_run_occluded_beams. The
// room's older scan from inside (its pose vouched for: min_agreement 0) has its beams
// through the cabinet's place outdated, and no other beam; with min_run_occluded_beams 0,
// none; unchanged, none.
TEST(ChangeDetection, ACabinetGlimpsedPastADoorJambOutdatesTheBeamsThroughIt) {
  World before = CorridorWithDoor(false), after = before;
  const double x0 = 11.6, x1 = 11.9, y0 = 4.0, y1 = 4.3;
  AddRectangle(x0, y0, x1, y1, &after);
  const Pose2 inside(14.5, 4.5, 3.14159265358979323846), corridor(17.0, 0.5, 2.2);
  const LaserScan older = SimulateScan(before, inside), newer = SimulateScan(after, corridor);
  int on_cabinet = 0;
  for (std::uint32_t b = 0; b < newer.ranges_m.size(); ++b) {
    const double a = corridor.theta + newer.Bearing(b), r = newer.ranges_m[b];
    const double x = corridor.x + r * std::cos(a), y = corridor.y + r * std::sin(a);
    on_cabinet += (x > x0 - 0.01 && x < x1 + 0.01 && y > y0 - 0.01 && y < y1 + 0.01) ? 1 : 0;
  }
  ASSERT_GE(on_cabinet, 1);
  ASSERT_LE(on_cabinet, 3);
  ChangeDetectionConfig vouched;
  vouched.min_agreement = 0.0;
  const ScanComparison c = CompareScans(older, inside, newer, corridor, vouched);
  ASSERT_TRUE(c.compared);
  ASSERT_FALSE(c.outdated.empty());
  for (const BeamCut& cut : c.outdated) {  // each crosses the desk's place before its return
    const double a = inside.theta + older.Bearing(cut.beam);
    const double t = (x1 - inside.x) / std::cos(a), y = inside.y + t * std::sin(a);
    EXPECT_GT(y, y0 - 0.4) << "beam " << cut.beam;
    EXPECT_LT(y, y1 + 0.4) << "beam " << cut.beam;
    EXPECT_LT(cut.free_to_m, older.ranges_m[cut.beam]);
  }
  vouched.min_run_occluded_beams = 0;
  EXPECT_TRUE(CompareScans(older, inside, newer, corridor, vouched).outdated.empty());
  // Unchanged, nothing is.
  vouched.min_run_occluded_beams = 2;
  const ScanComparison none =
      CompareScans(SimulateScan(after, inside), inside, newer, corridor, vouched);
  EXPECT_TRUE(none.outdated.empty()) << none.outdated.size();
}

}  // namespace
}  // namespace lifelong::slam
