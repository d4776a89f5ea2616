// Internal: the Box2D scene of a World (zero gravity, top view). Walls, doors and boxes are
// static bodies; the robot is a dynamic box so that Box2D stops it at walls. Doors are
// disabled while open, so they neither block the robot nor reflect the laser.
#pragma once

#include <box2d/box2d.h>

#include <memory>
#include <string>
#include <vector>

#include "sensor/pose2.hpp"
#include "sim/scenario.hpp"

namespace lifelong::sim {

/// A begin-contact event between the robot and something in the world.
struct ContactEvent {
  std::string what;  ///< "wall", "door <name>" or "box <name>"
};

class Physics : private b2ContactListener {
 public:
  Physics(const World& world, const RobotConfig& robot, const Pose2& T_world_robot);
  Physics(const Physics&) = delete;
  Physics& operator=(const Physics&) = delete;
  ~Physics() override;

  /// Opens and closes doors and moves boxes to their state at time t_s.
  void ApplyScripts(double t_s);
  /// One fixed step with the robot moving at the given world-frame velocity.
  void Step(double dt_s, double vx_mps, double vy_mps, double w_radps);
  Pose2 RobotPose() const;
  void SetRobotPose(const Pose2& T_world_robot);
  /// True while the robot touches anything.
  bool RobotTouching() const { return touching_ > 0; }
  /// Contacts begun since the last call.
  std::vector<ContactEvent> TakeContacts();
  /// Distance to the closest fixture other than the robot along the ray, or max_m.
  double CastRay(double x, double y, double angle_rad, double max_m) const;

 private:
  void BeginContact(b2Contact* contact) override;
  void EndContact(b2Contact* contact) override;
  std::string Describe(b2Fixture* f) const;

  const World& world_;
  std::unique_ptr<b2World> b2world_;
  b2Body* robot_ = nullptr;
  std::vector<b2Body*> doors_;
  std::vector<b2Body*> boxes_;
  std::vector<std::size_t> box_moves_done_;
  int touching_ = 0;
  std::vector<ContactEvent> contacts_;
};

}  // namespace lifelong::sim
