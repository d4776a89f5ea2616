// A 2D simulated world in metres: static walls (polylines and solid polygons), scripted
// doors, movable boxes, named places and a roadmap of collision-free edges between them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sim/geometry.hpp"

namespace lifelong::sim {

/// A chain of wall segments. `closed` polygons are solid obstacles (pillars, furniture):
/// nothing may be placed inside them. Open polylines are thin walls.
struct Wall {
  std::vector<Point> points;
  bool closed = false;
};

/// A door is a segment that blocks the laser and the robot while closed.
struct Door {
  std::string name;
  Segment segment;
  std::vector<std::pair<double, double>> closed_intervals_s;  ///< [begin, end) s, sorted
  bool IsClosed(double t_s) const;
};

/// A scripted relocation of a box at time t_s.
struct BoxMove {
  double t_s = 0.0;  ///< s
  Point center;      ///< m
  double yaw_rad = 0.0;
};

/// A rectangular box (furniture) that blocks laser and robot; it can be moved at set times.
struct Box {
  std::string name;
  Point center;                ///< m, initial
  double width_m = 0.5;        ///< along the box x axis
  double height_m = 0.5;       ///< along the box y axis
  double yaw_rad = 0.0;        ///< initial heading
  std::vector<BoxMove> moves;  ///< sorted by t_s
};

struct Place {
  std::string name;
  Point at;
};

struct World {
  std::string source;  ///< file the world came from ("" when built in code)
  std::vector<Wall> walls;
  std::vector<Door> doors;
  std::vector<Box> boxes;
  std::vector<Place> places;                 ///< file order
  std::vector<std::pair<int, int>> roadmap;  ///< edges as indices into places
  double clearance_m = 0.3;  ///< minimal distance of places and roadmap edges to walls

  /// Index of the place called `name`, or -1.
  int FindPlace(const std::string& name) const;
};

/// Static walls and polygon outlines as segments (x0, y0, x1, y1), metres.
std::vector<Segment> WallSegments(const World& world);
/// The door segments, in file order (whether or not they are closed).
std::vector<Segment> DoorSegments(const World& world);
/// The four outline segments of each box at its initial pose.
std::vector<Segment> BoxSegments(const World& world);

/// Distance from p to the nearest wall, door or box (initial pose) segment.
double ClearanceAt(const World& world, const Point& p);
/// Distance from segment s to the nearest wall or box segment (doors are passable).
double PathClearance(const World& world, const Segment& s);
/// True when p lies inside a solid polygon wall or a box.
bool InsideObstacle(const World& world, const Point& p);

/// Why a robot of clearance radius `clearance_m` cannot stand at p ("" when it can).
std::string CheckFree(const World& world, const Point& p, double clearance_m);
/// Why the straight drive a -> b is not free ("" when it is): crosses or grazes a wall.
std::string CheckPath(const World& world, const Point& a, const Point& b, double clearance_m);

}  // namespace lifelong::sim
