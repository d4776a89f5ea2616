#include <gtest/gtest.h>

#include <string>

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

}  // namespace
}  // namespace lifelong::sim
