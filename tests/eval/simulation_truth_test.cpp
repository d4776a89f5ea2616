// What the ground truth holds (issue #13): doors count as walls only when closed at some
// time of the run, and a tour that never visits every destination has no first pass.
#include <gtest/gtest.h>

#include <string>

#include "eval/experiment/simulation.hpp"
#include "eval/truth/world_state.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

sim::World OneWallOneDoor(std::vector<std::pair<double, double>> closed) {
  sim::World w;
  w.walls.push_back({{{0.0, 0.0}, {4.0, 0.0}}, false});
  sim::Door door;
  door.name = "d";
  door.segment = {4.0, 0.0, 5.0, 0.0};
  door.closed_intervals_s = std::move(closed);
  w.doors.push_back(door);
  return w;
}

bool HasDoor(const std::vector<Segment>& walls) {
  for (const Segment& s : walls) {
    if (s.x0 == 4.0 && s.x1 == 5.0) return true;
  }
  return false;
}

TEST(TrueWalls, ADoorNeverClosedIsNoWall) {
  const auto walls = TrueWalls(OneWallOneDoor({}), 1000.0);
  EXPECT_EQ(walls.size(), 1u);
  EXPECT_FALSE(HasDoor(walls));
}

TEST(TrueWalls, ADoorClosedOnlyAfterTheRunIsNoWall) {
  EXPECT_FALSE(HasDoor(TrueWalls(OneWallOneDoor({{100.0, 200.0}}), 50.0)));
  EXPECT_TRUE(HasDoor(TrueWalls(OneWallOneDoor({{100.0, 200.0}}), 150.0)));
  EXPECT_TRUE(HasDoor(TrueWalls(OneWallOneDoor({{0.0, 1e9}}), 10.0)));
}

TEST(TrueWalls, BoxesOnlyWhereTheyStoodDuringTheRun) {
  sim::World w;
  sim::Box box;
  box.center = {0.0, 0.0};
  box.width_m = box.height_m = 1.0;
  box.moves.push_back({100.0, {10.0, 0.0}, 0.0});
  w.boxes.push_back(box);
  EXPECT_EQ(TrueWalls(w, 50.0).size(), 4u);   // never moved
  EXPECT_EQ(TrueWalls(w, 150.0).size(), 8u);  // both poses
}

sim::Scenario Tour() {
  sim::Scenario s;
  s.world.places = {{"a", {0.0, 0.0}}, {"b", {10.0, 0.0}}, {"c", {20.0, 0.0}}};
  s.route.kind = sim::RouteConfig::Kind::kTour;
  s.route.tour_places = {0, 1, 2};
  return s;
}

Observation At(double t, double x) {
  Observation o;
  o.stamp_s = t;
  o.T_world_robot_true = Pose2(x, 0.0, 0.0);
  return o;
}

TEST(FirstPassEnd, ATourThatMissesADestinationHasNone) {
  SimulatedRun run;
  run.observations = {At(0.0, 0.0), At(5.0, 10.0), At(9.0, 12.0)};
  EXPECT_FALSE(FirstPassEnd(Tour(), run).has_value());
}

TEST(FirstPassEnd, ATourEndsItsFirstPassAtTheLastNewDestination) {
  SimulatedRun run;
  run.observations = {At(0.0, 0.0), At(5.0, 10.0), At(9.0, 20.0), At(12.0, 10.0)};
  ASSERT_TRUE(FirstPassEnd(Tour(), run).has_value());
  EXPECT_EQ(*FirstPassEnd(Tour(), run), 9.0);
}

// A world whose truth map would not fit in memory is refused, naming the world file, before
// anything is simulated (a 10 km wall asked OpenCV for 40 GB after the simulation).
TEST(CheckWorldRaster, AWorldPastTheRasterLimitIsAnInputError) {
  sim::Scenario scenario;
  scenario.world_path = "far.yaml";
  scenario.world.walls.push_back({{{0.0, 0.0}, {10000.0, 10000.0}}, false});
  try {
    CheckWorldRaster(scenario, 0.05);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "far.yaml");
    EXPECT_NE(std::string(e.what()).find("the world spans 10000 x 10000 m"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(CheckWorldRaster(scenario, 1.0));  // 10 000 x 10 000 cells fit
  scenario.world = OneWallOneDoor({});
  EXPECT_NO_THROW(CheckWorldRaster(scenario, 0.05));
}

}  // namespace
}  // namespace lifelong::eval
