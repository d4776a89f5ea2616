#include "sim/simulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "sim/scenario.hpp"
#include "tests/sim/test_worlds.hpp"

namespace lifelong::sim {
namespace {

using testing::OneWay;
using testing::WallAt;

const std::string kDir = LIFELONG_SOURCE_DIR;

TEST(Simulator, WallTwoMetresAheadReadsTwoMetres) {
  Scenario s = OneWay(WallAt(2.0, 5.0), {{0, 0}, {0.05, 0}});  // route done at once
  const Simulator ideal(s);
  const LaserScan scan = ideal.TrueScan(Pose2());
  ASSERT_EQ(scan.ranges_m.size(), 181u);
  EXPECT_NEAR(scan.ranges_m[90], 2.0, 1e-5);                             // straight ahead
  EXPECT_NEAR(scan.ranges_m[45], 2.0 * std::sqrt(2.0), 1e-5);            // 45 deg right
  EXPECT_EQ(scan.ranges_m[0], static_cast<float>(s.laser.range_max_m));  // along the wall

  s.laser.range_noise_m = 0.01;
  double sum = 0.0, sum2 = 0.0;
  const int runs = 100;
  for (int seed = 0; seed < runs; ++seed) {
    s.seed = seed;
    Simulator sim(s);
    Observation obs;
    ASSERT_TRUE(sim.Next(&obs, nullptr));
    const double err = obs.scan.ranges_m[90] - 2.0;
    sum += err;
    sum2 += err * err;
  }
  EXPECT_NEAR(sum / runs, 0.0, 0.004);               // 4 standard errors of 1 mm
  EXPECT_NEAR(std::sqrt(sum2 / runs), 0.01, 0.003);  // sampling spread of 100 runs
}

TEST(Simulator, NoSelfHitsInOpenSpace) {
  Scenario s = OneWay(World(), {{0, 0}, {1, 0}});
  s.laser.beams = 361;
  s.laser.fov_deg = 360.0;  // beams also cross the body behind the laser
  s.laser.T_robot_laser = Pose2(0.15, 0.0, 0.0);
  Simulator sim(s);
  Observation obs;
  int scans = 0;
  while (sim.Next(&obs, nullptr)) {
    ++scans;
    for (float r : obs.scan.ranges_m) ASSERT_EQ(r, static_cast<float>(s.laser.range_max_m));
  }
  EXPECT_GT(scans, 5);
}

TEST(Simulator, ZeroNoiseOdometryHasZeroDrift) {
  World w;  // a square drive with turns in open space
  Scenario s = OneWay(w, {{0, 0}, {3, 0}, {3, 3}, {0, 3}, {0, 0.5}});
  Simulator sim(s);
  Observation first, obs;
  std::vector<Odometry> odom;
  ASSERT_TRUE(sim.Next(&first, &odom));
  int n = 0;
  double max_err = 0.0;
  while (sim.Next(&obs, &odom)) {
    const Pose2 d_odom = Between(first.T_odom_robot, obs.T_odom_robot);
    const Pose2 d_true = Between(*first.T_world_robot_true, *obs.T_world_robot_true);
    max_err = std::max({max_err, std::abs(d_odom.x - d_true.x), std::abs(d_odom.y - d_true.y),
                        std::abs(NormalizeAngle(d_odom.theta - d_true.theta))});
    EXPECT_EQ(odom.size(), 4u);  // 20 Hz odometry between 5 Hz scans
    ++n;
  }
  EXPECT_GT(n, 50);
  EXPECT_LT(max_err, 1e-9);
  EXPECT_TRUE(sim.collisions().empty());
  EXPECT_NEAR(sim.true_pose().x, 0.0, 0.15);
  EXPECT_NEAR(sim.true_pose().y, 0.5, 0.15);
  EXPECT_FALSE(sim.timed_out());
}

// 200 straight drives of 5 m: the spread of the odometry error matches the slip model.
// With per-wheel variance k per metre rolled, the path length odometry measures has
// var = k D / 2 and the heading var = 2 k D / b^2 (b track width).
TEST(Simulator, OdometryNoiseStatisticsMatchConfig) {
  Scenario s = OneWay(World(), {{0, 0}, {5, 0}});
  s.odometry.slip_variance_m2_per_m = 1e-4;
  s.laser.beams = 2;
  const int runs = 200;
  double sl = 0, sll = 0, st = 0, stt = 0, distance = 0;
  for (int seed = 1; seed <= runs; ++seed) {
    s.seed = seed;
    Simulator sim(s);
    Observation obs;
    std::vector<Odometry> odom;
    Pose2 last;
    double length = 0.0;
    while (sim.Next(&obs, &odom)) {
      for (const Odometry& o : odom) {
        length += std::hypot(o.T_odom_robot.x - last.x, o.T_odom_robot.y - last.y);
        last = o.T_odom_robot;
      }
    }
    distance = obs.T_world_robot_true->x;
    const double el = length - distance;
    const double et = obs.T_odom_robot.theta;
    sl += el, sll += el * el, st += et, stt += et * et;
  }
  const double b = s.robot.track_width_m, k = 1e-4;
  const double var_l = sll / runs - (sl / runs) * (sl / runs);
  const double var_t = stt / runs - (st / runs) * (st / runs);
  // The run ends at the last scan before the 0.1 m waypoint tolerance is reached.
  EXPECT_NEAR(distance, 5.0, 0.25);
  EXPECT_NEAR(sl / runs, 0.0, 3 * std::sqrt(k * distance / 2 / runs) + 1e-3);
  // Sample variances of 200 runs have a relative standard error of 10 %; allow 35 %.
  EXPECT_NEAR(var_l / (k * distance / 2), 1.0, 0.35);
  EXPECT_NEAR(var_t / (2 * k * distance / (b * b)), 1.0, 0.35);
}

TEST(Simulator, DrivingIntoAWallIsACollisionNotAPassThrough) {
  Scenario s = OneWay(WallAt(2.0, 3.0), {{0, 0}, {4, 0}});  // the path crosses the wall
  Simulator sim(s);
  Observation obs;
  double max_x = 0.0;
  while (sim.Next(&obs, nullptr)) max_x = std::max(max_x, obs.T_world_robot_true->x);
  ASSERT_FALSE(sim.collisions().empty());
  EXPECT_EQ(sim.collisions().front().what, "wall");
  EXPECT_NEAR(sim.collisions().front().T_world_robot.x, 2.0 - 0.22, 0.03);
  EXPECT_LT(max_x, 2.0 - 0.2);  // half the 0.44 m footprint, within Box2D's skin
  EXPECT_TRUE(sim.timed_out());
}

TEST(Simulator, ClosedDoorBlocksLaserThenOpens) {
  World w;
  w.doors.push_back({"d", {2.0, -1.0, 2.0, 1.0}, {{0.0, 1.0}}});
  Scenario s = OneWay(w, {{0, 0}, {0.5, 0}});
  Simulator sim(s);
  Observation obs;
  ASSERT_TRUE(sim.Next(&obs, nullptr));
  EXPECT_NEAR(obs.scan.ranges_m[90], 2.0, 1e-5);  // t = 0, closed
  while (sim.Next(&obs, nullptr) && obs.stamp_s < 1.5) {
  }
  EXPECT_GE(obs.stamp_s, 1.0);
  EXPECT_EQ(obs.scan.ranges_m[90], static_cast<float>(s.laser.range_max_m));  // open
}

std::uint64_t HashRun(Scenario s, int scans) {
  Simulator sim(s);
  Observation obs;
  std::vector<Odometry> odom;
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over ranges and poses
  auto mix = [&h](const void* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
      h = (h ^ static_cast<const unsigned char*>(p)[i]) * 1099511628211ull;
  };
  for (int i = 0; i < scans && sim.Next(&obs, &odom); ++i) {
    mix(obs.scan.ranges_m.data(), obs.scan.ranges_m.size() * sizeof(float));
    mix(&obs.T_odom_robot, sizeof(Pose2));
    mix(&*obs.T_world_robot_true, sizeof(Pose2));
    for (const Odometry& o : odom) mix(&o.T_odom_robot, sizeof(Pose2));
  }
  return h;
}

TEST(Simulator, SameSeedSameStreamOtherSeedOtherStream) {
  Scenario s = LoadScenario(kDir + "/scenarios/corridor_3.yaml");
  const std::uint64_t a = HashRun(s, 150);
  EXPECT_EQ(a, HashRun(s, 150));
  s.seed += 1;
  EXPECT_NE(a, HashRun(s, 150));
}

TEST(Simulator, Corridor3RunsToTheEndWithoutCollisions) {
  const Scenario s = LoadScenario(kDir + "/scenarios/corridor_3.yaml");
  Simulator sim(s);
  Observation obs;
  int scans = 0;
  double last_progress = 0.0;
  while (sim.Next(&obs, nullptr)) {
    ++scans;
    EXPECT_GE(sim.progress(), last_progress);
    last_progress = sim.progress();
  }
  EXPECT_TRUE(sim.collisions().empty());
  EXPECT_FALSE(sim.timed_out());
  EXPECT_NEAR(sim.time_s(), s.duration_s, 0.15 * s.duration_s);
  EXPECT_EQ(scans, static_cast<int>(std::lround(sim.time_s() * 5.0)) + 1);
  EXPECT_NEAR(obs.T_world_robot_true->x, 1.0, 0.15);  // back at `west`
}

TEST(Simulator, Office5MinVisitsRoomsWithoutCollisions) {
  const Scenario s = LoadScenario(kDir + "/scenarios/office_5min.yaml");
  Simulator sim(s);
  Observation obs;
  std::set<int> rooms;  // rooms are 8 m wide, south of y = 8.5 m or north of y = 11 m
  while (sim.Next(&obs, nullptr)) {
    const Pose2& p = *obs.T_world_robot_true;
    if (p.y < 8.0 || p.y > 11.5) rooms.insert(static_cast<int>(p.x / 8.0) + (p.y > 10 ? 10 : 0));
  }
  EXPECT_NEAR(sim.time_s(), 300.0, 0.5);
  EXPECT_GE(rooms.size(), 2u);
  EXPECT_TRUE(sim.collisions().empty());
}

// Issue #16: the ten-minute twins drive their routes to the end without touching a wall,
// door or box (about 1.5 s each in Release).
std::vector<Pose2> RunTwin(const std::string& name) {
  const Scenario s = LoadScenario(kDir + "/scenarios/" + name + ".yaml");
  Simulator sim(s);
  Observation obs;
  std::vector<Pose2> path;
  while (sim.Next(&obs, nullptr)) path.push_back(*obs.T_world_robot_true);
  EXPECT_TRUE(sim.collisions().empty()) << name << ": " << sim.collisions().front().what;
  EXPECT_FALSE(sim.timed_out()) << name;
  EXPECT_NEAR(sim.time_s(), s.duration_s, 0.05 * s.duration_s) << name;
  return path;
}

TEST(Simulator, Warehouse10MinDrivesSeveralAislesWithoutCollisions) {
  std::set<int> aisles;  // aisle j has its centre at y = 1.3 + 3.8 j; the rows span x 4..33
  for (const Pose2& p : RunTwin("warehouse_10min")) {
    if (p.x > 6.0 && p.x < 31.0) aisles.insert(static_cast<int>(std::lround((p.y - 1.3) / 3.8)));
  }
  EXPECT_GE(aisles.size(), 2u);
}

TEST(Simulator, LongCorridor10MinReachesBothEndsWithoutCollisions) {
  double min_x = 1e9, max_x = -1e9;
  const std::vector<Pose2> path = RunTwin("long_corridor_10min");
  for (const Pose2& p : path) {
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
    EXPECT_GT(p.y, 0.5);  // in the corridor (y 0 .. 2.5), never in a room
    EXPECT_LT(p.y, 2.0);
  }
  EXPECT_LT(min_x, 1.2);
  EXPECT_GT(max_x, 70.8);
  EXPECT_NEAR(path.back().x, 1.0, 0.15);  // back at `west`
}

TEST(Simulator, BigLoop10MinDrivesOneLapWithoutCollisions) {
  const std::vector<Pose2> path = RunTwin("big_loop_10min");
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    length += std::hypot(path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
  }
  EXPECT_NEAR(length, 289.0, 3.0);         // the centre line of the ring
  EXPECT_NEAR(path.back().x, 46.0, 0.15);  // back at `s_mid`, where it started
  EXPECT_NEAR(path.back().y, 1.3, 0.15);
}

}  // namespace
}  // namespace lifelong::sim
