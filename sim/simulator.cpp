#include "sim/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>

#include "sim/controller.hpp"
#include "sim/odometry_model.hpp"
#include "sim/physics.hpp"
#include "sim/random_streams.hpp"
#include "sim/route.hpp"

namespace lifelong::sim {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

int TicksPer(double physics_hz, double rate_hz) {
  return std::max(1, static_cast<int>(std::lround(physics_hz / rate_hz)));
}

/// Back-and-forth: every step. Tour: the first leg (the rest comes leg by leg).
std::vector<RouteStep> FirstSteps(const Scenario& sc, int* place, std::mt19937_64* rng) {
  if (sc.route.kind != RouteConfig::Kind::kTour) return ExpandBackAndForth(sc.route);
  std::vector<RouteStep> steps;
  AppendTourLeg(sc.route, sc.world, place, rng, &steps);
  return steps;
}

Pose2 StartPose(const Scenario& sc, const std::vector<RouteStep>& steps) {
  const Point start = RouteStart(sc.route, sc.world);
  for (const RouteStep& s : steps) {
    if (s.kind == RouteStep::Kind::kGoto) {
      return {start.x, start.y, std::atan2(s.target.y - start.y, s.target.x - start.x)};
    }
  }
  return {start.x, start.y, 0.0};
}

}  // namespace

struct Simulator::Impl {
  explicit Impl(const Scenario& scenario)
      : sc(scenario),
        route_rng(StreamRng(sc.seed, RandomStream::kRoute)),
        odometry_rng(StreamRng(sc.seed, RandomStream::kOdometry)),
        laser_seed(DeriveSeed(sc.seed, static_cast<std::uint64_t>(RandomStream::kLaser))),
        tour_place(sc.route.start_place),
        steps(FirstSteps(sc, &tour_place, &route_rng)),
        true_pose(StartPose(sc, steps)),
        physics(sc.world, sc.robot, true_pose),
        odom(sc.odometry, sc.robot.track_width_m, Pose2()),
        controller(sc.robot),
        dt_s(1.0 / sc.physics_rate_hz),
        ticks_per_scan(TicksPer(sc.physics_rate_hz, sc.laser.rate_hz)),
        ticks_per_odom(TicksPer(sc.physics_rate_hz, sc.odometry.rate_hz)) {
    const bool tour = sc.route.kind == RouteConfig::Kind::kTour;
    time_limit_s = tour ? sc.route.tour_duration_s : 2.0 * sc.duration_s + 60.0;
  }

  double Time() const { return static_cast<double>(tick) * dt_s; }
  std::optional<DriveCommand> Command();
  bool Tick();
  bool TourDone() const;
  LaserScan Scan(const Pose2& T_world_robot, std::optional<std::uint64_t> noise_index) const;

  Scenario sc;
  std::mt19937_64 route_rng;     // tour destinations
  std::mt19937_64 odometry_rng;  // wheel slip, two draws per tick
  std::uint64_t laser_seed;      // scan k draws from DeriveSeed(laser_seed, k)
  int tour_place;                // tour: the destination of the last leg drawn
  std::vector<RouteStep> steps;
  Pose2 true_pose;
  Physics physics;
  WheelOdometry odom;
  WaypointController controller;
  double dt_s;
  int ticks_per_scan;
  int ticks_per_odom;
  double time_limit_s = 0.0;
  DriveCommand cmd;
  std::size_t step_index = 0;
  double stopped_s = 0.0;
  std::int64_t tick = 0;
  std::uint64_t scans = 0;  // observations emitted
  double last_stamp_s = 0.0;
  bool started = false;
  bool finished = false;
  bool timed_out = false;
  std::vector<Collision> collisions;
};

// The command for this tick; none once a back-and-forth route has run out of steps.
std::optional<DriveCommand> Simulator::Impl::Command() {
  for (;;) {
    if (step_index == steps.size() && sc.route.kind == RouteConfig::Kind::kTour) {
      AppendTourLeg(sc.route, sc.world, &tour_place, &route_rng, &steps);  // the next leg
    }
    if (step_index >= steps.size()) break;
    const RouteStep& s = steps[step_index];
    if (s.kind == RouteStep::Kind::kStop) {
      if (cmd.v_mps == 0.0 && cmd.w_radps == 0.0) stopped_s += dt_s;
      if (stopped_s < s.stop_s) return controller.Brake(cmd, dt_s);
      stopped_s = 0.0;
      ++step_index;
      continue;
    }
    if (!controller.Reached(true_pose, s.target)) {
      return controller.Toward(true_pose, s.target, cmd, dt_s);
    }
    ++step_index;
  }
  if (sc.route.kind != RouteConfig::Kind::kTour) return std::nullopt;
  return controller.Brake(cmd, dt_s);  // a tour that could not draw a leg (built in code)
}

// One physics step; false, changing nothing, once a back-and-forth route has run out.
bool Simulator::Impl::Tick() {
  physics.ApplyScripts(Time());
  const std::optional<DriveCommand> next_cmd = Command();
  if (!next_cmd) return false;
  cmd = *next_cmd;
  const double half_b = 0.5 * sc.robot.track_width_m;
  const WheelMotion m{(cmd.v_mps - cmd.w_radps * half_b) * dt_s,
                      (cmd.v_mps + cmd.w_radps * half_b) * dt_s};
  const Pose2 next = IntegrateWheels(true_pose, m, sc.robot.track_width_m);
  physics.Step(dt_s, (next.x - true_pose.x) / dt_s, (next.y - true_pose.y) / dt_s,
               NormalizeAngle(next.theta - true_pose.theta) / dt_s);
  const std::vector<ContactEvent> events = physics.TakeContacts();
  ++tick;
  for (const ContactEvent& e : events) collisions.push_back({Time(), e.what, true_pose});
  if (physics.RobotTouching() || !events.empty()) {
    true_pose = physics.RobotPose();  // Box2D stopped or deflected the robot
  } else {
    true_pose = next;  // keep the double-precision pose; Box2D state is float
    physics.SetRobotPose(next);
  }
  odom.Update(m, &odometry_rng);  // the wheels rolled m whether or not the robot was blocked
  return true;
}

bool Simulator::Impl::TourDone() const {
  return sc.route.kind == RouteConfig::Kind::kTour && Time() >= sc.route.tour_duration_s;
}

// Noise-free without `noise_index`; else with the noise of scan number *noise_index.
LaserScan Simulator::Impl::Scan(const Pose2& T_world_robot,
                                std::optional<std::uint64_t> noise_index) const {
  const LaserConfig& l = sc.laser;
  const bool noisy = noise_index.has_value();
  std::mt19937_64 rng(noisy ? DeriveSeed(laser_seed, *noise_index) : 0);
  LaserScan scan;
  scan.stamp_s = Time();
  scan.angle_min_rad = -0.5 * l.fov_deg * kDegToRad;
  scan.angle_increment_rad = l.fov_deg * kDegToRad / (l.beams - 1);
  scan.range_max_m = l.range_max_m;
  scan.T_robot_laser = l.T_robot_laser;
  scan.ranges_m.resize(static_cast<std::size_t>(l.beams));
  const Pose2 T_world_laser = T_world_robot * l.T_robot_laser;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double angle = T_world_laser.theta + scan.Bearing(i);
    double r = physics.CastRay(T_world_laser.x, T_world_laser.y, angle, l.range_max_m);
    if (noisy) {  // both draws for every beam, hit or not: beam i's noise is its own
      const double g = Gaussian(&rng);
      const double u = Uniform(&rng);
      if (r < l.range_max_m) r = std::clamp(r + l.range_noise_m * g, 0.0, l.range_max_m);
      if (u < l.dropout_prob) r = l.range_max_m;
    }
    scan.ranges_m[i] = static_cast<float>(r);
  }
  return scan;
}

Simulator::Simulator(const Scenario& scenario) : impl_(std::make_unique<Impl>(scenario)) {}
Simulator::~Simulator() = default;

bool Simulator::Next(Observation* obs, std::vector<Odometry>* odometry_since_last) {
  Impl& s = *impl_;
  if (odometry_since_last != nullptr) odometry_since_last->clear();
  if (s.finished) return false;
  auto emit_odom = [&] {
    if (odometry_since_last != nullptr && s.tick % s.ticks_per_odom == 0) {
      odometry_since_last->push_back({s.Time(), s.odom.pose()});
    }
  };
  if (!s.started) {
    s.started = true;
    emit_odom();
  } else {
    do {
      if (!s.Tick()) {
        // The route ended inside this scan interval: the run ends at the previous scan, so
        // a route with fewer repetitions is a prefix of one with more (no braking tail
        // that the longer route would not have).
        s.finished = true;
        if (odometry_since_last != nullptr) odometry_since_last->clear();
        return false;
      }
      emit_odom();
    } while (s.tick % s.ticks_per_scan != 0);
  }
  obs->stamp_s = s.Time();
  obs->T_odom_robot = s.odom.pose();
  obs->T_world_robot_true = s.true_pose;
  obs->scan = s.Scan(s.true_pose, s.scans++);
  s.last_stamp_s = obs->stamp_s;
  const bool done = s.TourDone();
  s.timed_out = !done && s.Time() >= s.time_limit_s;
  s.finished = done || s.timed_out;
  return true;
}

double Simulator::time_s() const { return impl_->last_stamp_s; }

double Simulator::progress() const {
  const Impl& s = *impl_;
  if (s.finished) return 1.0;
  if (s.sc.route.kind == RouteConfig::Kind::kTour) {
    return std::min(1.0, s.Time() / s.sc.route.tour_duration_s);
  }
  return s.steps.empty() ? 1.0 : static_cast<double>(s.step_index) / s.steps.size();
}

const std::vector<Collision>& Simulator::collisions() const { return impl_->collisions; }
bool Simulator::timed_out() const { return impl_->timed_out; }
const Pose2& Simulator::true_pose() const { return impl_->true_pose; }

LaserScan Simulator::TrueScan(const Pose2& T_world_robot) const {
  return impl_->Scan(T_world_robot, std::nullopt);
}

}  // namespace lifelong::sim
