#include "sim/world_loader.hpp"

#include <cmath>
#include <initializer_list>
#include <set>

#include "sensor/input_error.hpp"
#include "sim/yaml_fields.hpp"

namespace lifelong::sim {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

/// YAML reads .inf and .nan as numbers; no coordinate, size, angle or time may be one.
// Coordinates, sizes, angles and times of a world beyond this are corruption: Box2D works in
// floats, which a larger double overflows (its assertions abort the process), and 1e7 is
// also the longest scenario (s).
constexpr double kMaxWorldValue = 1e7;
constexpr const char* kOutOfBounds = "must be a finite number of magnitude at most 1e7";

void RequireBounded(const std::string& file, const YAML::Node& n, const std::string& field,
                    std::initializer_list<double> values) {
  for (double v : values) {
    if (!(std::abs(v) <= kMaxWorldValue)) Fail(file, n, field, kOutOfBounds);
  }
}

/// The same for the value of one key of `f`, blamed on that key's line and name.
void RequireBounded(const Fields& f, const std::string& key, std::initializer_list<double> values) {
  for (double v : values) {
    if (!(std::abs(v) <= kMaxWorldValue)) f.FailAt(key, kOutOfBounds);
  }
}

/// Polygons thinner than this (twice the area over the perimeter, the width of a thin
/// rectangle) are degenerate: the same 1e-6 m as a repeated point.
constexpr double kMinPolygonWidthM = 1e-6;

/// True when the closed polygon `ring` has (near-)zero area, e.g. collinear points.
bool ZeroArea(const std::vector<Point>& ring) {
  double twice_area = 0.0, perimeter = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point& a = ring[i];
    const Point& b = ring[(i + 1) % ring.size()];
    twice_area += a.x * b.y - b.x * a.y;
    perimeter += std::hypot(b.x - a.x, b.y - a.y);
  }
  return !(std::abs(twice_area) >= kMinPolygonWidthM * perimeter);
}

template <typename F>
void ForEachItem(Fields* f, const std::string& key, F&& fn) {
  const YAML::Node list = f->Optional(key);
  if (!list) return;
  if (!list.IsSequence()) Fail(f->file(), list, f->Name(key), "expected a list");
  for (std::size_t i = 0; i < list.size(); ++i) {
    fn(list[i], f->Name(key) + "[" + std::to_string(i) + "]");
  }
}

Wall ParseWall(const std::string& file, const YAML::Node& n, const std::string& field) {
  Fields f(file, n, field);
  Wall w;
  w.closed = f.Has("polygon");
  if (w.closed == f.Has("polyline")) Fail(file, n, field, "needs exactly one of polyline, polygon");
  const std::string key = w.closed ? "polygon" : "polyline";
  const YAML::Node pts = f.Required(key);
  w.points = AsPoints(file, pts, f.Name(key));
  for (const Point& p : w.points) RequireBounded(file, pts, f.Name(key), {p.x, p.y});
  f.Finish();
  if (w.points.size() < (w.closed ? 3u : 2u)) Fail(file, pts, f.Name(key), "too few points");
  for (const Segment& s : ToSegments(w.points, w.closed)) {
    if (std::hypot(s.x1 - s.x0, s.y1 - s.y0) < 1e-6) {
      Fail(file, pts, f.Name(key), "zero-length segment (repeated point)");
    }
  }
  if (w.closed && ZeroArea(w.points)) {
    Fail(file, pts, f.Name(key), "polygon has zero area (collinear points)");
  }
  if (w.closed && PolygonSelfIntersects(w.points)) {
    Fail(file, pts, f.Name(key), "polygon is self-intersecting");
  }
  return w;
}

Door ParseDoor(const std::string& file, const YAML::Node& n, const std::string& field) {
  Fields f(file, n, field);
  Door d;
  d.name = f.String("name");
  const Point a = f.GetPoint("from");
  RequireBounded(f, "from", {a.x, a.y});
  const Point b = f.GetPoint("to");
  RequireBounded(f, "to", {b.x, b.y});
  d.segment = {a.x, a.y, b.x, b.y};
  if (std::hypot(b.x - a.x, b.y - a.y) < 1e-6) Fail(file, n, field, "door has zero width");
  const YAML::Node iv = f.Optional("closed_s");
  if (iv) {
    if (!iv.IsSequence()) Fail(file, iv, f.Name("closed_s"), "expected [[t0, t1], ...]");
    for (const YAML::Node& p : iv) {
      const Point t = AsPoint(file, p, f.Name("closed_s"));
      RequireBounded(file, p, f.Name("closed_s"), {t.x, t.y});
      if (t.y < t.x) Fail(file, p, f.Name("closed_s"), "interval ends before it begins");
      d.closed_intervals_s.emplace_back(t.x, t.y);
    }
  }
  f.Finish();
  return d;
}

Box ParseBox(const std::string& file, const YAML::Node& n, const std::string& field) {
  Fields f(file, n, field);
  Box b;
  b.name = f.String("name");
  b.center = f.GetPoint("center");
  RequireBounded(f, "center", {b.center.x, b.center.y});
  const Point size = f.GetPoint("size");
  RequireBounded(f, "size", {size.x, size.y});
  if (size.x <= 0.0 || size.y <= 0.0) f.FailAt("size", "size must be positive");
  b.width_m = size.x;
  b.height_m = size.y;
  b.yaw_rad = f.Double("yaw_deg", 0.0) * kDegToRad;
  RequireBounded(f, "yaw_deg", {b.yaw_rad});
  ForEachItem(&f, "moves", [&](const YAML::Node& m, const std::string& name) {
    Fields mf(file, m, name);
    BoxMove mv{mf.Double("t_s"), mf.GetPoint("center"), mf.Double("yaw_deg", 0.0) * kDegToRad};
    mf.Finish();
    RequireBounded(mf, "t_s", {mv.t_s});
    RequireBounded(mf, "center", {mv.center.x, mv.center.y});
    RequireBounded(mf, "yaw_deg", {mv.yaw_rad});
    if (!b.moves.empty() && mv.t_s < b.moves.back().t_s) Fail(file, m, name, "moves not sorted");
    b.moves.push_back(mv);
  });
  f.Finish();
  return b;
}

}  // namespace

namespace {

void ParsePlaces(Fields* f, World* w) {
  ForEachItem(f, "places", [&](const YAML::Node& n, const std::string& name) {
    Fields pf(f->file(), n, name);
    Place p{pf.String("name"), pf.GetPoint("at")};
    pf.Finish();
    RequireBounded(pf, "at", {p.at.x, p.at.y});
    if (w->FindPlace(p.name) >= 0) Fail(f->file(), n, name, "duplicate place '" + p.name + "'");
    const std::string why = CheckFree(*w, p.at, w->clearance_m);
    if (!why.empty()) Fail(f->file(), n, name, "place '" + p.name + "' " + why);
    w->places.push_back(p);
  });
}

void ParseRoadmap(Fields* f, World* w) {
  ForEachItem(f, "roadmap", [&](const YAML::Node& n, const std::string& name) {
    if (!n.IsSequence() || n.size() != 2) Fail(f->file(), n, name, "expected [place, place]");
    int idx[2];
    for (int k = 0; k < 2; ++k) {
      const std::string p = AsString(f->file(), n[k], name);
      idx[k] = w->FindPlace(p);
      if (idx[k] < 0) Fail(f->file(), n[k], name, "unknown place '" + p + "'");
    }
    const std::string why =
        CheckPath(*w, w->places[idx[0]].at, w->places[idx[1]].at, w->clearance_m);
    if (!why.empty()) Fail(f->file(), n, name, "roadmap edge " + why);
    w->roadmap.emplace_back(idx[0], idx[1]);
  });
}

World ParseWorld(const YAML::Node& root, const std::string& file) {
  Fields f(file, root, "");
  World w;
  w.source = file;
  w.clearance_m = f.Double("clearance_m", w.clearance_m);
  if (!(w.clearance_m >= 0.0) || !std::isfinite(w.clearance_m))
    f.FailAt("clearance_m", "must be finite and >= 0");
  const YAML::Node walls = f.Required("walls");
  if (!walls.IsSequence() || walls.size() == 0)
    Fail(file, walls, "walls", "expected a non-empty list");
  ForEachItem(&f, "walls", [&](const YAML::Node& n, const std::string& name) {
    w.walls.push_back(ParseWall(file, n, name));
  });
  // Doors and boxes are named in collision reports and change metrics: one name, one object.
  std::set<std::string> object_names;
  auto unique_name = [&](const std::string& object, const YAML::Node& n, const std::string& name) {
    if (!object_names.insert(object).second) {
      Fail(file, n["name"], name + ".name", "duplicate door or box name '" + object + "'");
    }
  };
  ForEachItem(&f, "doors", [&](const YAML::Node& n, const std::string& name) {
    w.doors.push_back(ParseDoor(file, n, name));
    unique_name(w.doors.back().name, n, name);
  });
  ForEachItem(&f, "boxes", [&](const YAML::Node& n, const std::string& name) {
    w.boxes.push_back(ParseBox(file, n, name));
    unique_name(w.boxes.back().name, n, name);
  });
  ParsePlaces(&f, &w);
  ParseRoadmap(&f, &w);
  f.Finish();
  return w;
}

}  // namespace

World LoadWorld(const std::string& path) { return ParseWorld(ParseYamlFile(path), path); }

World LoadWorldFromString(const std::string& yaml, const std::string& name) {
  return ParseWorld(ParseYamlString(yaml, name), name);
}

}  // namespace lifelong::sim
