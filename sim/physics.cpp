#include "sim/physics.hpp"

#include <cmath>
#include <cstdint>

namespace lifelong::sim {
namespace {

// Fixture user data: kind in the high bits, index in the low bits.
enum Kind : std::uintptr_t { kRobot = 1, kWall = 2, kDoor = 3, kBox = 4 };
constexpr std::uintptr_t kShift = 24;

std::uintptr_t Tag(Kind kind, std::size_t index) { return (kind << kShift) | index; }
Kind KindOf(b2Fixture* f) { return static_cast<Kind>(f->GetUserData().pointer >> kShift); }
std::size_t IndexOf(b2Fixture* f) {
  return f->GetUserData().pointer & ((std::uintptr_t{1} << kShift) - 1);
}

b2Vec2 V(double x, double y) { return {static_cast<float>(x), static_cast<float>(y)}; }

void AddEdge(b2Body* body, const Segment& s, std::uintptr_t tag) {
  b2EdgeShape edge;
  edge.SetTwoSided(V(s.x0, s.y0), V(s.x1, s.y1));
  b2FixtureDef def;
  def.shape = &edge;
  def.userData.pointer = tag;
  body->CreateFixture(&def);
}

b2Body* StaticBody(b2World* w, double x, double y, double angle) {
  b2BodyDef def;
  def.type = b2_staticBody;
  def.position = V(x, y);
  def.angle = static_cast<float>(angle);
  return w->CreateBody(&def);
}

}  // namespace

Physics::Physics(const World& world, const RobotConfig& robot, const Pose2& T_world_robot)
    : world_(world), b2world_(std::make_unique<b2World>(b2Vec2(0.0f, 0.0f))) {
  b2world_->SetContactListener(this);
  b2Body* walls = StaticBody(b2world_.get(), 0, 0, 0);
  for (const Segment& s : WallSegments(world)) AddEdge(walls, s, Tag(kWall, 0));
  for (std::size_t i = 0; i < world.doors.size(); ++i) {
    doors_.push_back(StaticBody(b2world_.get(), 0, 0, 0));
    AddEdge(doors_.back(), world.doors[i].segment, Tag(kDoor, i));
  }
  for (std::size_t i = 0; i < world.boxes.size(); ++i) {
    const Box& b = world.boxes[i];
    boxes_.push_back(StaticBody(b2world_.get(), b.center.x, b.center.y, b.yaw_rad));
    b2PolygonShape shape;
    shape.SetAsBox(static_cast<float>(0.5 * b.width_m), static_cast<float>(0.5 * b.height_m));
    b2FixtureDef def;
    def.shape = &shape;
    def.userData.pointer = Tag(kBox, i);
    boxes_.back()->CreateFixture(&def);
  }
  box_moves_done_.assign(world.boxes.size(), 0);
  b2BodyDef def;
  def.type = b2_dynamicBody;
  def.position = V(T_world_robot.x, T_world_robot.y);
  def.angle = static_cast<float>(T_world_robot.theta);
  robot_ = b2world_->CreateBody(&def);
  b2PolygonShape shape;
  shape.SetAsBox(static_cast<float>(0.5 * robot.length_m), static_cast<float>(0.5 * robot.width_m));
  b2FixtureDef fdef;
  fdef.shape = &shape;
  fdef.density = 100.0f;  // ~17 kg over the footprint; value irrelevant against static walls
  fdef.friction = 0.0f;
  fdef.userData.pointer = Tag(kRobot, 0);
  robot_->CreateFixture(&fdef);
  ApplyScripts(0.0);
}

Physics::~Physics() { b2world_->SetContactListener(nullptr); }

void Physics::ApplyScripts(double t_s) {
  for (std::size_t i = 0; i < doors_.size(); ++i) {
    const bool closed = world_.doors[i].IsClosed(t_s);
    if (doors_[i]->IsEnabled() != closed) doors_[i]->SetEnabled(closed);
  }
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    const auto& moves = world_.boxes[i].moves;
    while (box_moves_done_[i] < moves.size() && moves[box_moves_done_[i]].t_s <= t_s) {
      const BoxMove& m = moves[box_moves_done_[i]++];
      boxes_[i]->SetTransform(V(m.center.x, m.center.y), static_cast<float>(m.yaw_rad));
    }
  }
}

void Physics::Step(double dt_s, double vx_mps, double vy_mps, double w_radps) {
  robot_->SetLinearVelocity(V(vx_mps, vy_mps));
  robot_->SetAngularVelocity(static_cast<float>(w_radps));
  b2world_->Step(static_cast<float>(dt_s), 8, 3);
}

Pose2 Physics::RobotPose() const {
  const b2Vec2 p = robot_->GetPosition();
  return {p.x, p.y, robot_->GetAngle()};
}

void Physics::SetRobotPose(const Pose2& T_world_robot) {
  robot_->SetTransform(V(T_world_robot.x, T_world_robot.y),
                       static_cast<float>(T_world_robot.theta));
}

std::vector<ContactEvent> Physics::TakeContacts() {
  std::vector<ContactEvent> out;
  out.swap(contacts_);
  return out;
}

void Physics::BeginContact(b2Contact* contact) {
  b2Fixture* a = contact->GetFixtureA();
  b2Fixture* b = contact->GetFixtureB();
  if (KindOf(a) != kRobot && KindOf(b) != kRobot) return;
  ++touching_;
  contacts_.push_back({Describe(KindOf(a) == kRobot ? b : a)});
}

void Physics::EndContact(b2Contact* contact) {
  if (KindOf(contact->GetFixtureA()) == kRobot || KindOf(contact->GetFixtureB()) == kRobot) {
    --touching_;
  }
}

std::string Physics::Describe(b2Fixture* f) const {
  switch (KindOf(f)) {
    case kDoor:
      return "door " + world_.doors[IndexOf(f)].name;
    case kBox:
      return "box " + world_.boxes[IndexOf(f)].name;
    default:
      return "wall";
  }
}

}  // namespace lifelong::sim

namespace lifelong::sim {
namespace {

// Keeps the closest hit; ignores the robot's own body (rays start inside it).
class ClosestHit : public b2RayCastCallback {
 public:
  explicit ClosestHit(const b2Body* ignore) : ignore_(ignore) {}
  float ReportFixture(b2Fixture* fixture, const b2Vec2&, const b2Vec2&, float fraction) override {
    if (fixture->GetBody() == ignore_) return -1.0f;
    fraction_ = fraction;
    return fraction;
  }
  float fraction() const { return fraction_; }

 private:
  const b2Body* ignore_;
  float fraction_ = 1.0f;
};

}  // namespace

double Physics::CastRay(double x, double y, double angle_rad, double max_m) const {
  ClosestHit hit(robot_);
  const b2Vec2 from = V(x, y);
  const b2Vec2 to = V(x + max_m * std::cos(angle_rad), y + max_m * std::sin(angle_rad));
  b2world_->RayCast(&hit, from, to);
  return hit.fraction() >= 1.0f ? max_m : static_cast<double>(hit.fraction()) * max_m;
}

}  // namespace lifelong::sim
