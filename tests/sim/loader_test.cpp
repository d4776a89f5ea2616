#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sensor/input_error.hpp"
#include "sim/scenario.hpp"
#include "sim/world_loader.hpp"

namespace lifelong::sim {
namespace {

const std::string kDir = LIFELONG_SOURCE_DIR;

// A 4 m x 2 m room with two places; `extra` is appended (lines 8 and on).
std::string Room(const std::string& extra) {
  return "walls:\n"                                                  // 1
         "  - polyline: [[0, 0], [4, 0], [4, 2], [0, 2], [0, 0]]\n"  // 2
         "places:\n"                                                 // 3
         "  - {name: a, at: [1, 1]}\n"                               // 4
         "  - {name: b, at: [3, 1]}\n"                               // 5
         "roadmap:\n"                                                // 6
         "  - [a, b]\n" +                                            // 7
         extra;
}

// Loads `yaml` and returns the error it raises (fails the test when none).
InputError WorldError(const std::string& yaml) {
  try {
    LoadWorldFromString(yaml, "w.yaml");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return InputError("", 0, "", "");
}

TEST(LoadWorld, ShippedWorldsLoad) {
  const World corridor = LoadWorld(kDir + "/worlds/corridor.yaml");
  EXPECT_EQ(corridor.places.size(), 3u);
  EXPECT_EQ(corridor.doors.size(), 2u);
  const World office = LoadWorld(kDir + "/worlds/office.yaml");
  EXPECT_GE(office.places.size(), 8u);
  EXPECT_EQ(DoorSegments(office).size(), office.doors.size());
  EXPECT_GT(WallSegments(office).size(), 30u);
}

// Every YAML file in a folder of the source tree, sorted.
std::vector<std::string> YamlFiles(const std::string& folder) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(kDir + "/" + folder)) {
    if (e.path().extension() == ".yaml") out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(LoadWorld, EveryShippedWorldLoads) {
  const std::vector<std::string> files = YamlFiles("worlds");
  EXPECT_GE(files.size(), 5u);
  for (const std::string& f : files) {
    const World w = LoadWorld(f);  // checks places and roadmap edges against the walls
    EXPECT_GE(w.places.size(), 2u) << f;
    EXPECT_FALSE(w.roadmap.empty()) << f;
  }
}

TEST(LoadWorld, Issue16Worlds) {
  // Seven aisles with a place at each end and in the middle cross aisle; the roadmap runs
  // through every aisle (2 edges each) and along the three cross aisles (6 edges each).
  const World warehouse = LoadWorld(kDir + "/worlds/warehouse.yaml");
  EXPECT_EQ(warehouse.places.size(), 21u);
  EXPECT_EQ(warehouse.roadmap.size(), 7u * 2u + 3u * 6u);
  EXPECT_EQ(warehouse.boxes.size(), 3u);
  const World corridor = LoadWorld(kDir + "/worlds/long_corridor.yaml");
  EXPECT_EQ(corridor.doors.size(), 8u);
  int closed_at_start = 0;
  for (const Door& d : corridor.doors) {
    closed_at_start += d.IsClosed(0.0);
    EXPECT_FALSE(d.closed_intervals_s.empty()) << d.name;
    EXPECT_LE(d.closed_intervals_s.back().second, 7200.0) << d.name;
  }
  EXPECT_EQ(closed_at_start, 4);  // s0, s2, s4, n6 closed; n1, n3, n4, s5 open
  const World loop = LoadWorld(kDir + "/worlds/big_loop.yaml");
  EXPECT_EQ(loop.places.size(), 8u);
  EXPECT_EQ(loop.roadmap.size(), 8u);  // a ring
  EXPECT_EQ(loop.doors.size(), 3u);
}

TEST(LoadWorld, RoomBuildsSegments) {
  const World w = LoadWorldFromString(Room(""), "w.yaml");
  EXPECT_EQ(WallSegments(w).size(), 4u);
  EXPECT_EQ(w.roadmap.size(), 1u);
  EXPECT_EQ(w.FindPlace("b"), 1);
}

TEST(LoadWorld, ErrorsNameFileLineField) {
  InputError e = WorldError(Room("doors:\n  - {name: d, from: [1, 0]}\n"));
  EXPECT_EQ(e.file(), "w.yaml");
  EXPECT_EQ(e.line(), 9);
  EXPECT_EQ(e.field(), "doors[0].to");  // missing field

  e = WorldError(Room("clearance_m: wide\n"));
  EXPECT_EQ(e.line(), 8);
  EXPECT_EQ(e.field(), "clearance_m");  // wrong type

  e = WorldError(Room("colour: red\n"));
  EXPECT_EQ(e.line(), 8);
  EXPECT_EQ(e.field(), "colour");  // unknown key

  e = WorldError("walls: []\n");
  EXPECT_EQ(e.field(), "walls");  // empty geometry
}

TEST(LoadWorld, RejectsBadGeometry) {
  InputError e = WorldError(
      "walls:\n"
      "  - polyline: [[0, 0], [4, 0]]\n"
      "  - polygon: [[0, 0], [2, 2], [2, 0], [0, 2]]\n");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.field(), "walls[1].polygon");

  // Place a inside a pillar; place b 0.1 m from the wall; an edge through a wall.
  e = WorldError(
      "walls:\n  - polygon: [[0.5, 0.5], [1.5, 0.5], [1.5, 1.5], [0.5, 1.5]]\n"
      "places:\n  - {name: a, at: [1, 1]}\n");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.field(), "places[0]");
  e = WorldError("walls:\n  - polyline: [[0, 0], [4, 0]]\nplaces:\n  - {name: b, at: [1, 0.1]}\n");
  EXPECT_EQ(e.field(), "places[0]");
  e = WorldError(
      "walls:\n  - polyline: [[2, -1], [2, 1]]\n"
      "places:\n  - {name: a, at: [1, 0]}\n  - {name: b, at: [3, 0]}\n"
      "roadmap:\n  - [a, b]\n");
  EXPECT_EQ(e.line(), 7);
  EXPECT_EQ(e.field(), "roadmap[0]");
}

TEST(LoadScenario, ShippedScenariosLoad) {
  for (const char* name : {"corridor_100", "corridor_3", "office_1h", "office_5min"}) {
    const Scenario s = LoadScenario(kDir + "/scenarios/" + name + ".yaml");
    EXPECT_EQ(s.name, name);
    EXPECT_GT(s.duration_s, 0.0);
  }
  const Scenario c100 = LoadScenario(kDir + "/scenarios/corridor_100.yaml");
  EXPECT_EQ(c100.route.repetitions, 100);
  // 200 legs of 18 m at 0.5 m/s, plus acceleration and turns: between 7200 s and 9000 s.
  EXPECT_GT(c100.duration_s, 7200.0);
  EXPECT_LT(c100.duration_s, 9000.0);
  EXPECT_EQ(LoadScenario(kDir + "/scenarios/office_1h.yaml").duration_s, 3600.0);
}

TEST(LoadScenario, EveryShippedScenarioLoads) {
  const std::vector<std::string> files = YamlFiles("scenarios");
  EXPECT_GE(files.size(), 11u);
  for (const std::string& f : files) {
    const Scenario s = LoadScenario(f);
    EXPECT_EQ(s.name, std::filesystem::path(f).stem().string()) << f;
    EXPECT_GT(s.duration_s, 0.0) << f;
  }
}

// Issue #16: each 2-hour scenario has a 10-minute twin with the same world, seed, models
// and route type.
TEST(LoadScenario, Issue16TwinsMatchTheirTwoHourScenarios) {
  for (const char* name : {"warehouse", "long_corridor", "big_loop"}) {
    const Scenario full = LoadScenario(kDir + "/scenarios/" + name + "_2h.yaml");
    const Scenario twin = LoadScenario(kDir + "/scenarios/" + name + "_10min.yaml");
    EXPECT_EQ(full.world_path, twin.world_path) << name;
    EXPECT_EQ(full.seed, twin.seed) << name;
    EXPECT_EQ(full.route.kind, twin.route.kind) << name;
    EXPECT_EQ(full.route.one_way, twin.route.one_way) << name;
    EXPECT_EQ(full.route.waypoints.size(), twin.route.waypoints.size()) << name;
    EXPECT_EQ(full.route.tour_places, twin.route.tour_places) << name;
    EXPECT_EQ(full.robot.max_speed_mps, twin.robot.max_speed_mps) << name;
    EXPECT_EQ(full.laser.beams, twin.laser.beams) << name;
    EXPECT_EQ(full.odometry.left_scale, twin.odometry.left_scale) << name;
    EXPECT_GT(full.duration_s, 6900.0) << name;  // about two hours
    EXPECT_LT(full.duration_s, 7500.0) << name;
    EXPECT_GT(twin.duration_s, 500.0) << name;  // about ten minutes
    EXPECT_LE(twin.duration_s, 610.0) << name;
  }
}

InputError ScenarioError(const std::string& yaml) {
  try {
    LoadScenarioFromString(yaml, "s.yaml", kDir + "/worlds");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << yaml;
  return InputError("", 0, "", "");
}

TEST(LoadScenario, ErrorsNameFileLineField) {
  const std::string head = "name: t\nworld: corridor.yaml\nseed: 1\n";  // lines 1-3
  InputError e = ScenarioError(head + "route:\n  type: back_and_forth\n");
  EXPECT_EQ(e.file(), "s.yaml");
  EXPECT_EQ(e.line(), 5);
  EXPECT_EQ(e.field(), "route.waypoints");
  e = ScenarioError(head +
                    "laser: {rate_hz: fast}\nroute: {type: tour, start: west, duration_s: 9}\n");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.field(), "laser.rate_hz");
  e = ScenarioError(head + "robot: {wheels: 3}\n");
  EXPECT_EQ(e.field(), "robot.wheels");
  // Waypoint (5, 0.1) is 0.1 m from the south wall: too close for the footprint.
  e = ScenarioError(head + "route:\n  type: path\n  waypoints: [west, [5, 0.1]]\n");
  EXPECT_EQ(e.line(), 6);
  EXPECT_EQ(e.field(), "route.waypoints[1]");
  e = ScenarioError(head + "route: {type: tour, start: nowhere, duration_s: 9}\n");
  EXPECT_EQ(e.field(), "route.start");
}

bool Says(const InputError& e, const std::string& text) {
  return std::string(e.what()).find(text) != std::string::npos;
}

// A value check names the key it checks and that key's line, not the section's first key
// or a neighbouring key (dropout_prob > 1 used to be reported as laser.range_noise_m).
TEST(LoadScenario, ValueChecksNameTheirOwnKeyAndLine) {
  const std::string head = "name: t\nworld: corridor.yaml\nseed: 1\n";  // lines 1-3
  InputError e = ScenarioError(head + "laser:\n  rate_hz: 5\n  range_noise_m: 0.01\n" +
                               "  dropout_prob: 1.5\n");
  EXPECT_EQ(e.line(), 7);
  EXPECT_EQ(e.field(), "laser.dropout_prob");
  e = ScenarioError(head + "laser:\n  rate_hz: 5\n  range_noise_m: .nan\n  dropout_prob: 0\n");
  EXPECT_EQ(e.line(), 6);
  EXPECT_EQ(e.field(), "laser.range_noise_m");
  e = ScenarioError(head + "odometry:\n  rate_hz: 20\n  slip_variance_m2_per_m: -1\n");
  EXPECT_EQ(e.line(), 6);
  EXPECT_EQ(e.field(), "odometry.slip_variance_m2_per_m");
  const InputError w = WorldError(
      Room("boxes:\n  - name: b\n    center: [2, 1]\n" + std::string("    size: [0, 1]\n")));
  EXPECT_EQ(w.line(), 11);
  EXPECT_EQ(w.field(), "boxes[0].size");
}

// yaml-cpp keeps the first of two equal keys; the loaders reject the second at its line.
TEST(LoadScenario, DuplicateKeysAreRejected) {
  const std::string head = "name: t\nworld: corridor.yaml\nseed: 1\n";  // lines 1-3
  InputError e = ScenarioError(head + "seed: 2\n");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.field(), "seed");
  EXPECT_TRUE(Says(e, "duplicate key")) << e.what();
  e = ScenarioError(head + "laser:\n  beams: 181\n  fov_deg: 180\n  beams: 361\n");
  EXPECT_EQ(e.line(), 7);
  EXPECT_EQ(e.field(), "laser.beams");
  EXPECT_TRUE(Says(e, "duplicate key")) << e.what();
}

TEST(LoadWorld, DuplicateKeysAreRejected) {
  InputError e = WorldError(Room("clearance_m: 0.3\nclearance_m: 5\n"));
  EXPECT_EQ(e.line(), 9);
  EXPECT_EQ(e.field(), "clearance_m");
  EXPECT_TRUE(Says(e, "duplicate key")) << e.what();
  e = WorldError(Room("boxes:\n  - {name: b, center: [2, 1], size: [1, 1], name: c}\n"));
  EXPECT_EQ(e.line(), 9);
  EXPECT_EQ(e.field(), "boxes[0].name");
  EXPECT_TRUE(Says(e, "duplicate key")) << e.what();
}

// A NaN waypoint aborted the process in Box2D, and one far away made a route of months.
TEST(LoadScenario, WaypointsMustBeFiniteAndRoutesAtMost1e7Seconds) {
  const std::string head = "name: t\nworld: corridor.yaml\nseed: 1\n";  // lines 1-3
  InputError e = ScenarioError(head + "route: {type: path, waypoints: [west, [.nan, 0]]}\n");
  EXPECT_EQ(e.field(), "route.waypoints[1]") << e.what();
  EXPECT_TRUE(Says(e, "finite")) << e.what();
  e = ScenarioError(
      head + "route: {type: back_and_forth, waypoints: [west, east], repetitions: 400000}\n");
  EXPECT_EQ(e.field(), "route") << e.what();
  EXPECT_TRUE(Says(e, "more than 1e7 s")) << e.what();
}

TEST(LoadScenario, FieldOfViewAndSpeedsHaveRanges) {
  const std::string head = "name: t\nworld: corridor.yaml\nseed: 1\n";  // lines 1-3
  const std::string route = "route: {type: back_and_forth, waypoints: [west, east]}\n";
  InputError e = ScenarioError(head + "laser:\n  fov_deg: 720\n" + route);
  EXPECT_EQ(e.line(), 5);
  EXPECT_EQ(e.field(), "laser.fov_deg");
  EXPECT_TRUE(Says(e, "(0, 360]")) << e.what();
  e = ScenarioError(head + "robot:\n  max_speed_mps: 1e9\n" + route);
  EXPECT_EQ(e.line(), 5);
  EXPECT_EQ(e.field(), "robot.max_speed_mps");
  EXPECT_TRUE(Says(e, "(0, 10] m/s")) << e.what();
  e = ScenarioError(head + "robot: {max_turn_rate_radps: 100}\n" + route);
  EXPECT_EQ(e.field(), "robot.max_turn_rate_radps");
  // The ends of the ranges load.
  const Scenario s = LoadScenarioFromString(
      head + "laser: {fov_deg: 360}\nrobot: {max_speed_mps: 10, max_turn_rate_radps: 6.28}\n" +
          route,
      "s.yaml", kDir + "/worlds");
  EXPECT_EQ(s.laser.fov_deg, 360.0);
  EXPECT_EQ(s.robot.max_speed_mps, 10.0);
}

// Three collinear points pass the repeated-point and self-intersection checks but enclose
// nothing: rejected like a two-point polygon.
TEST(LoadWorld, RejectsZeroAreaPolygons) {
  for (const char* ring : {"[[0, 1], [1, 1], [3, 1]]", "[[0, 1], [1, 1], [3, 1.0000000001]]"}) {
    const InputError e = WorldError(
        "walls:\n  - polyline: [[0, 0], [4, 0]]\n  - polygon: " + std::string(ring) + "\n");
    EXPECT_EQ(e.line(), 3) << ring;
    EXPECT_EQ(e.field(), "walls[1].polygon") << ring;
    EXPECT_TRUE(Says(e, "zero area")) << e.what();
  }
  // A small but real polygon (a 1 mm square) loads.
  const World w = LoadWorldFromString(
      "walls:\n  - polygon: [[0, 0], [1e-3, 0], [1e-3, 1e-3], [0, 1e-3]]\n", "w.yaml");
  EXPECT_EQ(w.walls.size(), 1u);
}

// Values a float overflows aborted the process in Box2D's assertions; they are refused at
// their key instead.
TEST(LoadWorld, ValuesPastAFloatAreRefusedAtTheirKey) {
  const std::string wall = "walls:\n  - polyline: [[0, 0], [4, 0]]\n";
  for (const auto& [text, field] : std::vector<std::pair<std::string, std::string>>{
           {"boxes:\n  - {name: b, center: [1, 1], size: [1, 1], yaw_deg: 1e300}\n",
            "boxes[0].yaw_deg"},
           {"boxes:\n  - {name: b, center: [1e39, 1], size: [1, 1]}\n", "boxes[0].center"},
           {"doors:\n  - {name: d, from: [0, 0], to: [1e8, 0]}\n", "doors[0].to"}}) {
    const InputError e = WorldError(wall + text);
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_TRUE(Says(e, "magnitude at most 1e7")) << e.what();
  }
}

}  // namespace
}  // namespace lifelong::sim
