#include "sim/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "sim/route.hpp"
#include "sim/world_loader.hpp"
#include "sim/yaml_fields.hpp"

namespace lifelong::sim {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
// Bounds that keep a typo (or a fuzzer) from asking for more memory or time than any
// experiment needs: 1e6 route legs, 1e7 s (about 4 months) of simulated time, 1e4 Hz physics,
// 1e5 laser beams.
constexpr double kMaxRouteLegs = 1e6;
constexpr double kMaxDurationS = 1e7;
constexpr double kMaxPhysicsRateHz = 1e4;
constexpr int kMaxBeams = 100000;
// Speed limits a ground robot scenario can sensibly ask for (the Pioneer 2-DX drives
// 0.5 m/s and turns 1 rad/s): 10 m/s (36 km/h) forward, 2 pi rad/s (a turn a second).
constexpr double kMaxSpeedMps = 10.0;
constexpr double kMaxTurnRateRadps = 2.0 * 3.14159265358979323846;

// Every check below blames the key it checks (Fields::FailAt: that key's line and dotted
// name), never the section map or a neighbouring key.
void Positive(Fields* f, const std::string& key, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) f->FailAt(key, "must be positive and finite");
}

void AtMost(Fields* f, const std::string& key, double value, double limit, const char* text) {
  if (value > limit) f->FailAt(key, std::string("must be <= ") + text);
}

RobotConfig ParseRobot(Fields f) {
  RobotConfig r;
  for (auto [key, v] : {std::pair{"length_m", &r.length_m},
                        {"width_m", &r.width_m},
                        {"track_width_m", &r.track_width_m},
                        {"max_speed_mps", &r.max_speed_mps},
                        {"max_accel_mps2", &r.max_accel_mps2},
                        {"max_turn_rate_radps", &r.max_turn_rate_radps},
                        {"max_turn_accel_radps2", &r.max_turn_accel_radps2},
                        {"waypoint_tolerance_m", &r.waypoint_tolerance_m}}) {
    *v = f.Double(key, *v);
    Positive(&f, key, *v);
  }
  if (r.max_speed_mps > kMaxSpeedMps)
    f.FailAt("max_speed_mps", "must be in (0, 10] m/s for a ground robot");
  if (r.max_turn_rate_radps > kMaxTurnRateRadps)
    f.FailAt("max_turn_rate_radps", "must be in (0, 2 pi] rad/s (one turn a second)");
  f.Finish();
  return r;
}

LaserConfig ParseLaser(Fields f) {
  LaserConfig l;
  l.rate_hz = f.Double("rate_hz", l.rate_hz);
  Positive(&f, "rate_hz", l.rate_hz);
  l.beams = f.Int("beams", l.beams);
  if (l.beams < 2 || l.beams > kMaxBeams) f.FailAt("beams", "needs 2 to 100000 beams");
  l.fov_deg = f.Double("fov_deg", l.fov_deg);
  if (!(l.fov_deg > 0.0 && l.fov_deg <= 360.0)) f.FailAt("fov_deg", "must be in (0, 360] deg");
  l.range_max_m = f.Double("range_max_m", l.range_max_m);
  Positive(&f, "range_max_m", l.range_max_m);
  l.range_noise_m = f.Double("range_noise_m", l.range_noise_m);
  if (!(l.range_noise_m >= 0.0) || !std::isfinite(l.range_noise_m))
    f.FailAt("range_noise_m", "must be finite and >= 0 m");
  l.dropout_prob = f.Double("dropout_prob", l.dropout_prob);
  if (!(l.dropout_prob >= 0.0 && l.dropout_prob <= 1.0))
    f.FailAt("dropout_prob", "must be in [0, 1]");
  if (f.Has("mount")) {
    const YAML::Node m = f.Required("mount");
    if (!m.IsSequence() || m.size() != 3)
      Fail(f.file(), m, f.Name("mount"), "expected [x, y, yaw_deg]");
    l.T_robot_laser =
        Pose2(AsDouble(f.file(), m[0], f.Name("mount")), AsDouble(f.file(), m[1], f.Name("mount")),
              AsDouble(f.file(), m[2], f.Name("mount")) * kDegToRad);
    if (!std::isfinite(l.T_robot_laser.x) || !std::isfinite(l.T_robot_laser.y) ||
        !std::isfinite(l.T_robot_laser.theta)) {
      Fail(f.file(), m, f.Name("mount"), "must be finite");
    }
  }
  f.Finish();
  return l;
}

OdometryConfig ParseOdometry(Fields f) {
  OdometryConfig o;
  o.rate_hz = f.Double("rate_hz", o.rate_hz);
  Positive(&f, "rate_hz", o.rate_hz);
  o.slip_variance_m2_per_m = f.Double("slip_variance_m2_per_m", o.slip_variance_m2_per_m);
  if (!(o.slip_variance_m2_per_m >= 0.0) || !std::isfinite(o.slip_variance_m2_per_m))
    f.FailAt("slip_variance_m2_per_m", "must be finite and >= 0");
  for (auto [key, v] : {std::pair{"left_scale", &o.left_scale},
                        {"right_scale", &o.right_scale},
                        {"track_scale", &o.track_scale}}) {
    *v = f.Double(key, *v);
    Positive(&f, key, *v);
  }
  f.Finish();
  return o;
}

Point ParseWaypoint(const std::string& file, const YAML::Node& n, const std::string& field,
                    const World& world) {
  if (n.IsScalar()) {
    const int i = world.FindPlace(n.Scalar());
    if (i < 0) Fail(file, n, field, "unknown place '" + n.Scalar() + "'");
    return world.places[i].at;
  }
  const Point p = AsPoint(file, n, field);
  // NaN aborted Box2D and a point far outside the world made a route of months.
  if (!(std::abs(p.x) <= 1e7 && std::abs(p.y) <= 1e7)) {
    Fail(file, n, field, "must be finite numbers of magnitude at most 1e7");
  }
  return p;
}

int ParsePlace(const std::string& file, const YAML::Node& n, const std::string& field,
               const World& world) {
  const std::string name = AsString(file, n, field);
  const int i = world.FindPlace(name);
  if (i < 0) Fail(file, n, field, "unknown place '" + name + "'");
  return i;
}

}  // namespace

namespace {

void ParseBackAndForth(Fields* f, const World& world, const RobotConfig& robot, RouteConfig* r) {
  const YAML::Node wps = f->Required("waypoints");
  const std::string field = f->Name("waypoints");
  if (!wps.IsSequence() || wps.size() < 2)
    Fail(f->file(), wps, field, "needs at least 2 waypoints");
  for (std::size_t i = 0; i < wps.size(); ++i) {
    const std::string name = field + "[" + std::to_string(i) + "]";
    const Point p = ParseWaypoint(f->file(), wps[i], name, world);
    std::string why = CheckFree(world, p, robot.Radius());
    if (!why.empty()) Fail(f->file(), wps[i], name, "waypoint " + why);
    // A leg of zero length ([west, west]) is reached as it starts: the route would end
    // with one scan and "0 s expected".
    if (i > 0 && std::hypot(p.x - r->waypoints.back().x, p.y - r->waypoints.back().y) <=
                     robot.waypoint_tolerance_m) {
      Fail(f->file(), wps[i], name,
           "waypoint is where waypoint " + std::to_string(i - 1) +
               " is (within robot.waypoint_tolerance_m): the leg has no length");
    }
    if (i > 0) why = CheckPath(world, r->waypoints.back(), p, 0.5 * robot.width_m + 0.05);
    if (!why.empty()) Fail(f->file(), wps[i], name, "path to waypoint " + why);
    r->waypoints.push_back(p);
  }
  r->repetitions = f->Int("repetitions", 1);
  if (r->repetitions < 1) f->FailAt("repetitions", "must be >= 1");
  if (static_cast<double>(r->repetitions) * static_cast<double>(wps.size()) > kMaxRouteLegs)
    f->FailAt("repetitions", "repetitions x waypoints must be at most 1e6 route legs");
}

void ParseTour(Fields* f, const World& world, const RobotConfig& robot, RouteConfig* r) {
  r->start_place = ParsePlace(f->file(), f->Required("start"), f->Name("start"), world);
  r->tour_duration_s = f->Double("duration_s");
  Positive(f, "duration_s", r->tour_duration_s);
  AtMost(f, "duration_s", r->tour_duration_s, kMaxDurationS, "1e7 s");
  const YAML::Node list = f->Optional("places");
  if (list && !list.IsSequence()) Fail(f->file(), list, f->Name("places"), "expected a list");
  const std::size_t n = list ? list.size() : world.places.size();
  for (std::size_t i = 0; i < n; ++i) {
    const YAML::Node node = list ? list[i] : f->node()["start"];
    const std::string name = f->Name("places") + "[" + std::to_string(i) + "]";
    const int p = list ? ParsePlace(f->file(), list[i], name, world) : static_cast<int>(i);
    std::string why = CheckFree(world, world.places[p].at, robot.Radius());
    if (why.empty() && ShortestPath(world, r->start_place, p).empty()) why = "is unreachable";
    if (!why.empty()) Fail(f->file(), node, name, "place '" + world.places[p].name + "' " + why);
    if (p != r->start_place || list) r->tour_places.push_back(p);
  }
  if (r->tour_places.size() < 2) f->FailAt("places", "needs 2 or more places");
  // A tour that can never leave its start would spin AppendTourLeg without moving.
  if (std::all_of(r->tour_places.begin(), r->tour_places.end(),
                  [&](int p) { return p == r->start_place; })) {
    f->FailAt("places", "needs a place other than the start");
  }
}

RouteConfig ParseRoute(Fields f, const World& world, const RobotConfig& robot) {
  RouteConfig r;
  const std::string type = f.String("type");
  r.stop_s = f.Double("stop_s", 0.0);
  if (!(r.stop_s >= 0.0) || r.stop_s > kMaxDurationS) f.FailAt("stop_s", "must be in [0, 1e7] s");
  if (type == "back_and_forth" || type == "path") {
    r.kind = RouteConfig::Kind::kBackAndForth;
    r.one_way = type == "path";
    ParseBackAndForth(&f, world, robot, &r);
  } else if (type == "tour") {
    r.kind = RouteConfig::Kind::kTour;
    ParseTour(&f, world, robot, &r);
  } else {
    f.FailAt("type", "expected back_and_forth, path or tour");
  }
  f.Finish();
  return r;
}

Scenario ParseScenario(const YAML::Node& root, const std::string& file,
                       const std::string& base_dir) {
  Fields f(file, root, "");
  Scenario s;
  s.source = file;
  s.name = f.String("name");
  const std::string world_rel = f.String("world");
  s.world_path = (std::filesystem::path(base_dir) / world_rel).lexically_normal().string();
  std::error_code error;  // a too-long or unreadable path is "not found", not an exception
  if (!std::filesystem::is_regular_file(s.world_path, error)) {  // no device, FIFO, folder
    Fail(file, root["world"], "world", "world file not found: " + s.world_path);
  }
  s.world = LoadWorld(s.world_path);
  const YAML::Node seed = f.Required("seed");
  try {
    s.seed = seed.as<std::uint64_t>();
  } catch (const YAML::Exception&) {
    Fail(file, seed, "seed", "expected a non-negative integer");
  }
  s.physics_rate_hz = f.Double("physics_rate_hz", s.physics_rate_hz);
  Positive(&f, "physics_rate_hz", s.physics_rate_hz);
  AtMost(&f, "physics_rate_hz", s.physics_rate_hz, kMaxPhysicsRateHz, "1e4 Hz");
  const YAML::Node empty(YAML::NodeType::Map);
  auto section = [&](const char* key) {
    const YAML::Node n = f.Optional(key);
    return Fields(file, n ? n : empty, key);
  };
  s.robot = ParseRobot(section("robot"));
  s.laser = ParseLaser(section("laser"));
  s.odometry = ParseOdometry(section("odometry"));
  s.route = ParseRoute(Fields(file, f.Required("route"), "route"), s.world, s.robot);
  s.collisions_expected = f.Bool("collisions_expected", false);
  f.Finish();
  EstimateDuration(&s);
  if (!(s.duration_s <= kMaxDurationS)) {
    Fail(file, f.Required("route"), "route",
         "the route takes " + std::to_string(s.duration_s) + " s, more than 1e7 s");
  }
  return s;
}

}  // namespace

double RobotConfig::Radius() const { return 0.5 * std::hypot(length_m, width_m); }

Scenario LoadScenario(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return ParseScenario(ParseYamlFile(path), path, dir.empty() ? "." : dir);
}

Scenario LoadScenarioFromString(const std::string& yaml, const std::string& name,
                                const std::string& base_dir) {
  return ParseScenario(ParseYamlString(yaml, name), name, base_dir);
}

void EstimateDuration(Scenario* s) {
  if (s->route.kind == RouteConfig::Kind::kTour) {
    s->duration_s = s->route.tour_duration_s;
    return;
  }
  const auto steps = ExpandBackAndForth(s->route);
  s->duration_s = EstimateStepsDuration(steps, RouteStart(s->route, s->world), s->robot);
}

}  // namespace lifelong::sim
