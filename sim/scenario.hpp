// A simulation scenario: a world, a Pioneer 2-DX with a SICK LMS-200, odometry noise, a
// route and a seed. Corridor experiment after the seed's section 6.1 (100 traversals forth
// and back in a 20 m x 3 m corridor); office tour after section 6.2 (about an hour).
//
// YAML (see scenarios/*.yaml): name, world (relative to the scenario file), seed,
// optional physics_rate_hz, optional collisions_expected (true/false) and sections robot / laser
// (mount: [x, y, yaw_deg]) / odometry whose keys are the fields below (each key at most once;
// numbers in the ranges given there, else an InputError naming that key's own line), and route, one
// of
//   {type: back_and_forth, waypoints: [place or [x, y], ...], repetitions: N, stop_s: 0}
//   {type: path, waypoints: [...]}                      # driven once, no way back
//   {type: tour, start: place, places: [...], duration_s: 3600, stop_s: 2}
//
// `seed` (a non-negative integer) never drives one generator for everything: it is split
// into three independent streams (sim/random_streams.hpp), route choices (the tour's
// destinations), odometry noise (wheel slip, two draws per physics tick) and laser noise
// (scan k seeded from the seed and k alone). So a short twin (same world, seed, models and
// route, a shorter duration_s or fewer repetitions) observes exactly the first part of its
// long scenario's stream (true poses, odometry, every range), and a tour over the same
// path with other route draws sees the same noise. For that, a back_and_forth or path run
// ends at the last scan before its final waypoint is reached (or its final stop is over),
// without braking to a standstill the longer route would not have.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sensor/pose2.hpp"
#include "sim/world.hpp"

namespace lifelong::sim {

/// Pioneer 2-DX: rectangular footprint, differential drive.
struct RobotConfig {
  double length_m = 0.44;              ///< footprint along the robot x axis
  double width_m = 0.38;               ///< footprint across
  double track_width_m = 0.33;         ///< distance between the wheel contact points
  double max_speed_mps = 0.5;          ///< forward speed limit, (0, 10] m/s
  double max_accel_mps2 = 0.5;         ///< forward acceleration limit
  double max_turn_rate_radps = 1.0;    ///< yaw rate limit, (0, 2 pi] rad/s
  double max_turn_accel_radps2 = 2.0;  ///< yaw acceleration limit
  double waypoint_tolerance_m = 0.1;   ///< a waypoint counts as reached within this
  /// Radius of the circle around the footprint, m.
  double Radius() const;
};

/// SICK LMS-200 scanning in the robot's plane.
struct LaserConfig {
  double rate_hz = 5.0;                ///< scans per second (rounded to whole physics steps)
  int beams = 181;                     ///< 181 (1 deg) or 361 (0.5 deg) over the field of view
  double fov_deg = 180.0;              ///< field of view, (0, 360], centred on the laser x axis
  double range_max_m = 30.0;           ///< no return reads exactly this
  double range_noise_m = 0.01;         ///< Gaussian range noise, standard deviation, >= 0
  double dropout_prob = 0.0;           ///< probability a beam reads range_max_m, [0, 1]
  Pose2 T_robot_laser{0.1, 0.0, 0.0};  ///< mount on the robot (inside the footprint)
};

/// Wheel odometry error model: per-wheel slip plus systematic calibration error.
struct OdometryConfig {
  double rate_hz = 20.0;                   ///< ODOM messages per second
  double slip_variance_m2_per_m = 2.5e-5;  ///< per wheel: var(measured - true) per m rolled
  double left_scale = 1.022;               ///< measured / true travel of the left wheel
  double right_scale = 1.018;              ///< measured / true travel of the right wheel
  double track_scale = 1.01;               ///< track width odometry assumes / true width
};

struct RouteConfig {
  enum class Kind { kBackAndForth, kTour };
  Kind kind = Kind::kBackAndForth;
  std::vector<Point> waypoints;  ///< back-and-forth: the path driven forth, then back
  int repetitions = 1;           ///< back-and-forth: number of forth-and-back cycles
  bool one_way = false;          ///< drive the waypoints once, without coming back ("path")
  int start_place = -1;          ///< tour: index into World::places
  std::vector<int> tour_places;  ///< tour: candidate destinations (indices into places)
  double tour_duration_s = 0.0;  ///< tour: simulated time to keep touring
  double stop_s = 0.0;           ///< pause at each end (back-and-forth) or destination (tour)
};

struct Scenario {
  std::string name;
  std::string source;      ///< scenario file ("" when built in code)
  std::string world_path;  ///< resolved path of the world file
  World world;
  RobotConfig robot;
  LaserConfig laser;
  OdometryConfig odometry;
  RouteConfig route;
  std::uint64_t seed = 1;          ///< split into the route, odometry and laser streams
  double physics_rate_hz = 100.0;  ///< fixed Box2D step rate
  /// The robot is meant to touch something (a test of the simulator, a push): a collision
  /// does not fail `run` or `simulate` (key collisions_expected, default false). A route
  /// that times out fails them still.
  bool collisions_expected = false;
  /// Expected simulated duration, s: exact for tours, an estimate for back-and-forth
  /// (path length, acceleration and turns). For progress bars and log_duration_s hints.
  double duration_s = 0.0;
};

/// Throws lifelong::InputError (file, 1-based line, dotted field) on bad input: missing
/// field, wrong type, unknown or duplicate key, a number out of its range, waypoint or place
/// inside or too close to a wall.
Scenario LoadScenario(const std::string& path);
/// The same from YAML text; the world path is resolved against `base_dir`.
Scenario LoadScenarioFromString(const std::string& yaml, const std::string& name,
                                const std::string& base_dir);

/// Fills scenario->duration_s from the route (call after building a Scenario in code).
void EstimateDuration(Scenario* scenario);

}  // namespace lifelong::sim
