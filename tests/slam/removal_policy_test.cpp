// Removal policies (slam/removal/removal_policy.hpp): which node goes, by name.
#include "slam/removal/removal_policy.hpp"

#include <algorithm>
#include <memory>

#include <gtest/gtest.h>

#include "slam/grid/beam_cut.hpp"
#include "slam/grid/change_detection.hpp"
#include "synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

const std::map<NodeId, double> kGains{{4, 9.0}, {7, 2.0}, {9, 2.0}, {12, 30.0}};

TEST(RemovalPolicy, InformationGainTakesTheLowestAtOrBelowTheThreshold) {
  const auto policy = MakeRemovalPolicy("information-gain", {5.0, 0, {}, {}});
  ASSERT_NE(policy, nullptr);
  EXPECT_EQ(policy->Name(), "information-gain");
  EXPECT_EQ(policy->Next(kGains, 100), NodeId{7});  // 7 and 9 tie: the smaller id
  EXPECT_EQ(policy->Next({{4, 9.0}, {12, 30.0}}, 100), std::nullopt);
  EXPECT_EQ(policy->Next({{4, 5.0}}, 100), NodeId{4});  // at the threshold: goes
  EXPECT_EQ(policy->Next({}, 100), std::nullopt);
}

TEST(RemovalPolicy, InformationGainAlsoRemovesPastItsBudget) {
  const auto policy = MakeRemovalPolicy("information-gain", {0.0, 50, {}, {}});
  EXPECT_EQ(policy->Next({{4, 9.0}, {12, 30.0}}, 51), NodeId{4});
  EXPECT_EQ(policy->Next({{4, 9.0}, {12, 30.0}}, 50), std::nullopt);
}

TEST(RemovalPolicy, NodeBudgetRemovesOnlyPastTheBudgetWhateverTheGain) {
  const auto policy = MakeRemovalPolicy("node-budget", {0.0, 50, {}, {}});
  ASSERT_NE(policy, nullptr);
  EXPECT_EQ(policy->Next({{4, 9.0}, {12, 30.0}}, 51), NodeId{4});
  EXPECT_EQ(policy->Next(kGains, 50), std::nullopt);  // gains of 2 bits stay within budget
  const auto unbounded = MakeRemovalPolicy("node-budget", {0.0, 0, {}, {}});
  EXPECT_EQ(unbounded->Next(kGains, 1000), std::nullopt);
}

// A footprint of a box of returns [x0, x1] x [y0, y1] (its corners and centre).
ScanFootprint Box(double x0, double y0, double x1, double y1, int edges) {
  ScanFootprint f;
  f.points = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {0.5 * (x0 + x1), 0.5 * (y0 + y1)}};
  for (const auto& p : f.points) f.box.extend(p);
  f.centre = f.box.center();
  f.edges = edges;
  return f;
}

// slam_toolbox's rule (removal_policy_overlap.cpp) on hand-made footprints: the current
// scan is node 100, covering [0, 10] x [0, 4].
TEST(RemovalPolicy, OverlapRemovesTheOlderOfTwoOverlappingScans) {
  const auto policy = MakeRemovalPolicy("overlap", {});
  ASSERT_NE(policy, nullptr);
  std::map<NodeId, ScanFootprint> scans;
  scans[100] = Box(0, 0, 10, 4, 2);
  scans[10] = Box(0, 0, 10, 4, 2);   // the same place, lightly tied: goes at once (IoU 1)
  scans[20] = Box(2, 0, 12, 4, 4);   // overlaps 80 %, tied by four edges: decays
  scans[30] = Box(0, 0, 10, 4, 1);   // one edge only: never a candidate
  scans[95] = Box(0, 0, 10, 4, 2);   // within the scan buffer: keeps its score
  scans[40] = Box(40, 0, 50, 4, 3);  // far away
  RoundView view;
  view.current = 100;
  view.footprint = [&](NodeId id) { return scans.at(id); };
  std::map<NodeId, double> gains{{10, 0.0}, {20, 0.0}, {30, 0.0}, {95, 0.0}, {40, 0.0}};
  policy->BeginRound(gains, view);
  EXPECT_EQ(policy->Next(gains, 200), NodeId{10});
  gains.erase(10);
  policy->Forget(10);
  EXPECT_EQ(policy->Next(gains, 199), std::nullopt);  // 20's score fell from 1 to 0.799
  // Each new scan over the same place takes o = 0.5 min(area 0.8, readings 3/5) = 0.3 and
  // the nearby penalty off 20's score, after the small boost of its edges
  // (k = min(o, 0.05 * (4 - 2)) = 0.1): 1 -> 0.799 -> 0.578 -> 0.335 -> 0.067 < 0.1.
  int rounds = 1;
  while (!policy->Next(gains, 199) && rounds < 10) {
    policy->BeginRound(gains, view);
    ++rounds;
  }
  EXPECT_EQ(rounds, 4);
  EXPECT_EQ(policy->Next(gains, 199), NodeId{20});
}

// DPG-SLAM's rule (removal_policy_dpg.cpp): the door of a room seen closed by nodes 1 and 2,
// open by node 9 (the current one). The door fills 29 % of node 1's view, 16 % of node 2's.
TEST(RemovalPolicy, DpgRetiresTheOutdatedBeamsAndTheNodesThatMostlyShowThePast) {
  testing::World closed, open;
  testing::AddRectangle(0.0, 0.0, 10.0, 6.0, &closed);
  testing::AddRectangle(0.0, 0.0, 10.0, 6.0, &open);
  closed.push_back({6.0, 2.0, 6.0, 4.0});
  std::map<NodeId, LaserScan> scans;
  std::map<NodeId, Pose2> poses{{1, {4.0, 3.0, 0.0}}, {2, {2.0, 3.0, 0.0}}, {9, {2.5, 2.9, 0.1}}};
  scans[1] = testing::SimulateScan(closed, poses[1]);
  scans[2] = testing::SimulateScan(closed, poses[2]);
  scans[9] = testing::SimulateScan(open, poses[9]);
  std::map<NodeId, std::vector<BeamCut>> cut;
  RoundView view;
  view.current = 9;
  view.nearby = {1, 2};
  view.scan = [&](NodeId id) { return ScanAt{&scans.at(id), &cut[id], poses.at(id)}; };
  RemovalPolicyConfig config;
  config.dpg.min_active_share = 0.75;
  const auto policy = MakeRemovalPolicy("dpg", config);
  ASSERT_NE(policy, nullptr);
  std::map<NodeId, double> gains{{1, 50.0}, {2, 60.0}};  // both far above the threshold
  policy->BeginRound(gains, view);
  const std::vector<SampleRetirement> out = policy->TakeRetirements();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].node, NodeId{1});
  EXPECT_EQ(out[1].node, NodeId{2});
  EXPECT_GT(out[0].cuts.size(), 46u);  // of 181 returns: under 75 % left
  EXPECT_GT(out[1].cuts.size(), 20u);
  EXPECT_LT(out[1].cuts.size(), 40u);
  EXPECT_TRUE(policy->TakeRetirements().empty());  // taken once
  // Node 1 has under 75 % of its returns left: it goes whatever its gain; node 2 stays.
  EXPECT_EQ(policy->Next(gains, 100), NodeId{1});
  gains.erase(1);
  EXPECT_EQ(policy->Next(gains, 100), std::nullopt);
  // The retired beams are no evidence: the next round retires nothing more of node 2.
  for (const SampleRetirement& r : out) cut[r.node] = r.cuts;
  policy->BeginRound(gains, view);
  EXPECT_TRUE(policy->TakeRetirements().empty());
  // A scan that shows no change is judged by the seed's rule.
  EXPECT_EQ(policy->Next({{2, 4.0}}, 100), NodeId{2});

  // A change seen a part at a time (here: every other beam of node 2's was cut before): the
  // beams cut before still join their neighbours' run, and the rest is cut, none twice.
  std::vector<BeamCut> half;
  for (std::size_t i = 0; i < out[1].cuts.size(); i += 2) half.push_back(out[1].cuts[i]);
  cut[2] = half;
  policy->BeginRound(gains, view);
  const std::vector<SampleRetirement> rest = policy->TakeRetirements();
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_EQ(rest[0].node, NodeId{2});
  EXPECT_EQ(rest[0].cuts.size(), out[1].cuts.size() - half.size());
  for (const BeamCut& c : rest[0].cuts) {
    EXPECT_TRUE(
        std::none_of(half.begin(), half.end(), [&](const BeamCut& h) { return h.beam == c.beam; }));
  }
}

// Node 1 saw the door of a room closed (x = 6, y in [2, 4]); node 9, later, sees it open.
struct DoorOpened {
  std::map<NodeId, Pose2> poses{{1, {4.0, 3.0, 0.0}}, {9, {2.5, 2.9, 0.1}}};
  std::map<NodeId, LaserScan> scans;
  std::map<NodeId, std::vector<BeamCut>> cut;

  DoorOpened() {
    testing::World closed, open;
    testing::AddRectangle(0.0, 0.0, 10.0, 6.0, &closed);
    testing::AddRectangle(0.0, 0.0, 10.0, 6.0, &open);
    closed.push_back({6.0, 2.0, 6.0, 4.0});
    scans[1] = testing::SimulateScan(closed, poses.at(1));
    scans[9] = testing::SimulateScan(open, poses.at(9));
  }
  DoorOpened(const DoorOpened&) = delete;  // View() holds this
  /// Node 9's round, with no node nearby.
  RoundView View() {
    RoundView view;
    view.current = 9;
    view.scan = [this](NodeId id) { return ScanAt{&scans.at(id), &cut[id], poses.at(id)}; };
    return view;
  }
};

// A node no round may remove (the newest, or one of an unsettled loop closure) is no
// candidate, yet its scan shows the past: its outdated beams are cut all the same, and it
// never goes.
TEST(RemovalPolicy, DpgCutsTheBeamsOfANodeNoRoundRemoves) {
  DoorOpened door;
  RoundView view = door.View();
  view.nearby = {1};
  RemovalPolicyConfig config;
  config.dpg.min_active_share = 0.75;
  const auto policy = MakeRemovalPolicy("dpg", config);
  policy->BeginRound({}, view);  // node 1 protected: no candidate
  const std::vector<SampleRetirement> out = policy->TakeRetirements();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_GT(out[0].cuts.size(), 46u);  // as when it was a candidate: under 75 % left
  EXPECT_EQ(policy->Next({}, 100), std::nullopt);
  EXPECT_EQ(policy->Next({{7, 50.0}}, 100), std::nullopt);  // node 1 is not doomed
}

// With compare_radius_m, the current scan is compared with every node within that distance,
// not only the round's: an older scan from farther off (a corridor looking into a room)
// crossed what the current one sees standing, and is cut all the same.
TEST(RemovalPolicy, DpgComparesEveryNodeWithinItsRadius) {
  DoorOpened door;
  RoundView view = door.View();  // node 1 is outside the round's radius: not nearby
  std::vector<double> asked;
  view.within = [&](double radius_m) {
    asked.push_back(radius_m);
    return std::vector<NodeId>{1};
  };
  RemovalPolicyConfig config;
  config.dpg.compare_radius_m = 0.0;
  const auto off = MakeRemovalPolicy("dpg", config);
  off->BeginRound({}, view);
  EXPECT_TRUE(off->TakeRetirements().empty());
  EXPECT_TRUE(asked.empty());
  config.dpg.compare_radius_m = 12.0;
  const auto on = MakeRemovalPolicy("dpg", config);
  on->BeginRound({}, view);
  const std::vector<SampleRetirement> out = on->TakeRetirements();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].node, NodeId{1});
  EXPECT_GT(out[0].cuts.size(), 46u);
  EXPECT_EQ(asked, std::vector<double>{12.0});
}

// Node 2 saw a partition 1 m in front of it, since taken away: most of what it shares with
// the current scan changed, so the two agree too little to be compared. Node 1, an older
// scan of the room as it stands, agrees with the current one: once it vouches for the current
// pose (it lies outside the front end's local map), node 2 is compared down to
// min_agreement_vouched, and its partition cut.
TEST(RemovalPolicy, DpgComparesAMostlyChangedScanOnceAnOlderOneVouchesForThePose) {
  testing::World now, then;
  testing::AddRectangle(0.0, 0.0, 10.0, 6.0, &now);
  testing::AddRectangle(0.0, 0.0, 10.0, 6.0, &then);
  then.push_back({5.0, 0.2, 5.0, 5.8});
  std::map<NodeId, Pose2> poses{{1, {3.0, 2.0, 0.2}}, {2, {4.0, 3.0, 0.0}}, {9, {2.5, 2.9, 0.1}}};
  std::map<NodeId, LaserScan> scans{{1, testing::SimulateScan(now, poses.at(1))},
                                    {2, testing::SimulateScan(then, poses.at(2))},
                                    {9, testing::SimulateScan(now, poses.at(9))}};
  std::map<NodeId, std::vector<BeamCut>> cut;
  RoundView view;
  view.current = 9;
  view.nearby = {1, 2};
  view.scan = [&](NodeId id) { return ScanAt{&scans.at(id), &cut[id], poses.at(id)}; };
  const ScanComparison alone =
      CompareScans(scans.at(2), poses.at(2), scans.at(9), poses.at(9), ChangeDetectionConfig{});
  ASSERT_FALSE(alone.compared);
  const auto cut_nodes = [&](NodeId local_map_from, double vouched) {
    RemovalPolicyConfig config;
    config.dpg.min_agreement_vouched = vouched;
    view.local_map_from = local_map_from;
    const auto policy = MakeRemovalPolicy("dpg", config);
    policy->BeginRound({}, view);
    std::vector<NodeId> out;
    for (const SampleRetirement& r : policy->TakeRetirements()) {
      if (r.cuts.size() > 50u) out.push_back(r.node);
    }
    return out;
  };
  EXPECT_EQ(cut_nodes(9, 0.0), std::vector<NodeId>{2});
  EXPECT_TRUE(cut_nodes(1, 0.0).empty());  // node 1 is in the local map: no voucher
  EXPECT_TRUE(cut_nodes(9, 0.6).empty());  // no lower bar than min_agreement
}

// A 10 m x 6 m room with a partition at x = 6 and a door in it (y in [2, 4]), closed or
// open, and a 0.5 m x 1 m box behind it or none.
testing::World PartitionedRoom(bool door_closed, bool box) {
  testing::World w;
  testing::AddRectangle(0.0, 0.0, 10.0, 6.0, &w);
  w.push_back({6.0, 0.0, 6.0, 2.0});
  w.push_back({6.0, 4.0, 6.0, 6.0});
  if (door_closed) w.push_back({6.0, 2.0, 6.0, 4.0});
  if (box) testing::AddRectangle(8.0, 2.5, 8.5, 3.5, &w);
  return w;
}

// Node 1's scan compared by the DPG rule (its defaults) with newer ones, round by round, its
// cuts kept as the mapper keeps them (MergeCuts).
struct DpgRounds {
  std::map<NodeId, Pose2> poses;
  std::map<NodeId, LaserScan> scans;
  std::map<NodeId, std::vector<BeamCut>> cut;
  std::unique_ptr<RemovalPolicy> policy = MakeRemovalPolicy("dpg", RemovalPolicyConfig{});

  void Add(NodeId id, const testing::World& w, const Pose2& pose) {
    poses[id] = pose;
    scans[id] = testing::SimulateScan(w, pose);
  }
  /// The round of node `current`: node 1's fresh cuts (none: empty).
  std::vector<BeamCut> Round(NodeId current) {
    RoundView view;
    view.current = current;
    view.nearby = {1};
    view.scan = [this](NodeId id) { return ScanAt{&scans.at(id), &cut[id], poses.at(id)}; };
    policy->BeginRound({}, view);
    const std::vector<SampleRetirement> out = policy->TakeRetirements();
    if (out.empty()) return {};
    EXPECT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].node, NodeId{1});
    cut[1] = MergeCuts(cut[1], out[0].cuts);
    return out[0].cuts;
  }
};

// A beam cut before is cut again where a later verdict takes out more: node 1 saw a box
// through an open door; node 9 sees the box gone (node 1's returns on it are cut, free up to
// them), node 10 the door closed, so those beams are now free only up to short of the door.
TEST(RemovalPolicy, DpgCutsABeamAgainWhenALaterChangeStandsNearerOnIt) {
  DpgRounds d;
  d.Add(1, PartitionedRoom(false, true), {2.0, 3.0, 0.0});
  d.Add(9, PartitionedRoom(false, false), {2.5, 2.9, 0.1});
  d.Add(10, PartitionedRoom(true, false), {3.0, 3.1, -0.05});
  std::vector<std::uint32_t> box;  // node 1's beams whose return on the box went
  for (const BeamCut& c : d.Round(9)) {
    if (!c.Resumes() && d.scans[1].ranges_m[c.beam] < 6.6f) box.push_back(c.beam);
  }
  ASSERT_GE(box.size(), 4u);
  const std::vector<BeamCut> again = d.Round(10);
  for (const std::uint32_t b : box) {
    const auto c =
        std::find_if(again.begin(), again.end(), [&](const BeamCut& x) { return x.beam == b; });
    ASSERT_NE(c, again.end()) << "beam " << b;
    EXPECT_LT(c->free_to_m, 3.9f) << "beam " << b;  // short of the door, 4 m along it
    EXPECT_GT(c->free_to_m, 3.0f) << "beam " << b;
  }
}

// The same change seen again from a pose a few centimetres away cuts no beam again: its
// verdicts differ from the first by pose noise (23 of the beams without the slack), and
// retracing the scan for them would only cost time.
TEST(RemovalPolicy, DpgDoesNotCutABeamAgainForCentimetres) {
  DpgRounds d;
  d.Add(1, PartitionedRoom(false, false), {2.0, 3.0, 0.0});
  d.Add(9, PartitionedRoom(true, false), {2.5, 2.9, 0.1});
  d.Add(10, PartitionedRoom(true, false), {2.53, 2.87, 0.1});
  const std::vector<BeamCut> first = d.Round(9);
  ASSERT_GE(first.size(), 20u);
  int recut = 0;  // beams of the first verdict cut again (a beam seen anew may be cut)
  for (const BeamCut& c : d.Round(10)) {
    recut +=
        std::any_of(first.begin(), first.end(), [&](const BeamCut& f) { return f.beam == c.beam; });
  }
  EXPECT_EQ(recut, 0);
}

TEST(RemovalPolicy, NamesAreTheRegistry) {
  for (const std::string& name : RemovalPolicyNames()) {
    const auto policy = MakeRemovalPolicy(name, {});
    ASSERT_NE(policy, nullptr) << name;
    EXPECT_EQ(policy->Name(), name);
  }
  EXPECT_EQ(MakeRemovalPolicy("gain", {}), nullptr);
}

}  // namespace
}  // namespace lifelong::slam
