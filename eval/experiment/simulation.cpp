#include "eval/experiment/simulation.hpp"

#include "eval/truth/world_state.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <ostream>
#include <set>
#include <sstream>

#include "eval/common/interrupt.hpp"
#include "eval/common/progress.hpp"
#include "eval/common/raster_limit.hpp"
#include "eval/figures/draw.hpp"
#include "eval/metrics/map_quality.hpp"
#include "eval/truth/world_state.hpp"
#include "io/carmen_log.hpp"
#include "io/map_file.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

std::string Stem(const std::string& log_path) {
  std::string s = log_path;
  for (const char* ext : {".gz", ".clf", ".log"}) {
    const std::string e(ext);
    if (s.size() > e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0) {
      s.resize(s.size() - e.size());
    }
  }
  return s;
}

}  // namespace

SimulatedRun SimulateScenario(const sim::Scenario& scenario, std::ostream* progress,
                              bool terminal) {
  sim::Simulator simulator(scenario);
  SimulatedRun run;
  Observation obs;
  std::vector<Odometry> odometry;
  ProgressOptions options;
  options.label = "simulate";
  options.unit = "sim s";
  options.terminal = terminal;
  ProgressMeter meter(progress, scenario.duration_s, options);
  while (simulator.Next(&obs, &odometry)) {
    ThrowIfInterrupted();
    run.odometry.insert(run.odometry.end(), odometry.begin(), odometry.end());
    run.observations.push_back(obs);
    // progress() is the share of the route done; time_s() the simulated time.
    meter.Update(simulator.progress() * scenario.duration_s, simulator.time_s(),
                 "scans " + std::to_string(run.observations.size()));
  }
  meter.Finish(simulator.time_s(), "scans " + std::to_string(run.observations.size()));
  run.collisions = simulator.collisions();
  run.timed_out = simulator.timed_out();
  run.duration_s = simulator.time_s();
  return run;
}

SimulationOutcome Outcome(const sim::Scenario& scenario, const SimulatedRun& run) {
  SimulationOutcome o;
  o.collided = !run.collisions.empty();
  o.timed_out = run.timed_out;
  o.collisions_expected = scenario.collisions_expected;
  o.collisions = static_cast<std::int64_t>(run.collisions.size());
  if (o.collided) {
    o.first_collision_s = run.collisions.front().stamp_s;
    o.first_collision_with = run.collisions.front().what;
  }
  o.duration_s = run.duration_s;
  o.expected_duration_s = scenario.duration_s;
  return o;
}

std::string OutcomeText(const SimulationOutcome& o) {
  std::ostringstream s;
  if (o.collided) {
    s << o.collisions << (o.collisions == 1 ? " collision" : " collisions")
      << ", the first at t = " << *o.first_collision_s << " s with "
      << o.first_collision_with.value_or("?")
      << (o.collisions_expected ? " (the scenario expects collisions)" : "") << "\n";
  }
  if (o.timed_out) {
    s << "the route timed out: " << o.duration_s << " s simulated, " << o.expected_duration_s
      << " s expected\n";
  }
  return s.str();
}

std::optional<double> FirstPassEnd(const sim::Scenario& scenario, const SimulatedRun& run) {
  const double end = run.observations.empty() ? 0.0 : run.observations.back().stamp_s;
  if (scenario.route.kind == sim::RouteConfig::Kind::kBackAndForth) {
    return end / std::max(1, scenario.route.repetitions);
  }
  std::set<int> pending(scenario.route.tour_places.begin(), scenario.route.tour_places.end());
  for (const Observation& o : run.observations) {
    for (auto it = pending.begin(); it != pending.end();) {
      const auto& p = scenario.world.places[static_cast<std::size_t>(*it)].at;
      const Pose2& T = *o.T_world_robot_true;
      it = std::hypot(T.x - p.x, T.y - p.y) < 0.5 ? pending.erase(it) : std::next(it);
    }
    if (pending.empty()) return o.stamp_s;
  }
  return std::nullopt;  // some destination never visited: no first pass
}

void CheckWorldRaster(const sim::Scenario& scenario, double resolution_m) {
  const sim::World& w = scenario.world;
  // The box of everything the truth raster draws: walls, doors, boxes where they ever stand.
  double x0 = std::numeric_limits<double>::max(), y0 = x0;
  double x1 = std::numeric_limits<double>::lowest(), y1 = x1;
  const auto add = [&](double x, double y, double r) {
    x0 = std::min(x0, x - r), y0 = std::min(y0, y - r);
    x1 = std::max(x1, x + r), y1 = std::max(y1, y + r);
  };
  for (const sim::Wall& wall : w.walls) {
    for (const sim::Point& p : wall.points) add(p.x, p.y, 0.0);
  }
  for (const sim::Door& d : w.doors) {
    add(d.segment.x0, d.segment.y0, 0.0);
    add(d.segment.x1, d.segment.y1, 0.0);
  }
  for (const sim::Box& b : w.boxes) {
    const double r = std::hypot(b.width_m, b.height_m);
    add(b.center.x, b.center.y, r);
    for (const sim::BoxMove& m : b.moves) add(m.center.x, m.center.y, r);
  }
  for (const sim::Place& p : w.places) add(p.at.x, p.at.y, 0.0);
  if (x0 > x1) return;  // nothing to draw
  const double cells = ((x1 - x0) / resolution_m + 1.0) * ((y1 - y0) / resolution_m + 1.0);
  if (cells <= kMaxRasterCells) return;
  std::ostringstream what;
  what << "the world spans " << std::lround(x1 - x0) << " x " << std::lround(y1 - y0)
       << " m: a map of it at " << resolution_m << " m needs " << cells << " cells, more than "
       << kMaxRasterCells << " (a larger world needs a coarser grid.resolution_m)";
  throw InputError(scenario.world_path, 0, "", what.str());
}

void WriteSimulation(const std::string& log_path, const sim::Scenario& scenario,
                     const SimulatedRun& run, double resolution_m) {
  const std::string stem = Stem(log_path);
  {
    io::CarmenWriter writer(log_path);
    writer.WriteParam("lifelong_scenario", scenario.name);
    writer.WriteParam("lifelong_seed", std::to_string(scenario.seed));
    std::size_t k = 0;
    for (const Observation& o : run.observations) {
      while (k < run.odometry.size() && run.odometry[k].stamp_s <= o.stamp_s) {
        writer.WriteOdometry(run.odometry[k++]);
      }
      writer.WriteScan(o);
    }
    while (k < run.odometry.size()) writer.WriteOdometry(run.odometry[k++]);
    writer.Close();
  }
  std::vector<StampedPose> truth;
  TrajectoryOverlay true_path{TrajectoryKind::kTrue, {}};
  TrajectoryOverlay odom_path{TrajectoryKind::kOdometry, {}};
  const Pose2 T_world_odom = run.observations.empty()
                                 ? Pose2()
                                 : *run.observations.front().T_world_robot_true *
                                       run.observations.front().T_odom_robot.Inverse();
  for (const Observation& o : run.observations) {
    truth.push_back({o.stamp_s, *o.T_world_robot_true});
    true_path.poses.push_back(*o.T_world_robot_true);
    odom_path.poses.push_back(T_world_odom * o.T_odom_robot);
  }
  io::WriteTum(stem + ".truth.tum", truth);
  const GroundTruth truth_walls = TruthOf(scenario.world, run.duration_s);
  const std::vector<Segment>& walls = truth_walls.walls;
  io::WritePgmMap(stem + ".truth.pgm", RasterizeWalls(walls, resolution_m));
  WriteTruthWalls(stem + ".truth.", truth_walls);
  DrawConfig draw;
  draw.world_resolution_m = resolution_m;
  WriteWorldPng(stem + ".png", walls, {true_path, odom_path}, draw);
}

}  // namespace lifelong::eval
