// Scan Context in 2D (slam/loops/place_descriptor.hpp) and the index over its ring keys
// (slam/loops/place_index.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "slam/loops/place_descriptor.hpp"
#include "slam/loops/place_index.hpp"

namespace lifelong::slam {
namespace {

// An irregular room: walls at different distances, a pillar, a niche; points every 5 cm.
std::vector<Eigen::Vector2d> Room() {
  std::vector<Eigen::Vector2d> pts;
  auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const int n = static_cast<int>((b - a).norm() / 0.05);
    for (int k = 0; k <= n; ++k) pts.push_back(a + (b - a) * (static_cast<double>(k) / n));
  };
  wall({-3, -2}, {7, -2});
  wall({7, -2}, {7, 4});
  wall({7, 4}, {2, 4});
  wall({2, 4}, {2, 5.5});
  wall({2, 5.5}, {-3, 5.5});
  wall({-3, 5.5}, {-3, -2});
  wall({3, 0.5}, {3.4, 0.5});
  wall({3.4, 0.5}, {3.4, 0.9});
  return pts;
}

std::vector<Eigen::Vector2d> Rotated(const std::vector<Eigen::Vector2d>& pts, double yaw) {
  const Eigen::Rotation2Dd R(yaw);
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : pts) out.push_back(R * p);
  return out;
}

TEST(PlaceDescriptor, TheSamePlaceTurnedKeepsItsRingKeyAndGivesItsHeading) {
  const PlaceDescriptorConfig c;
  const PlaceDescriptor a = DescribePlace(Room(), c);
  EXPECT_GT(a.occupied, 30);
  EXPECT_NEAR(ComparePlaces(a, a).distance, 0.0, 1e-6);
  for (double yaw : {0.5, -1.2, 2.9}) {
    // The robot turned by yaw at the same spot: it sees the room turned by -yaw.
    const PlaceDescriptor b = DescribePlace(Rotated(Room(), -yaw), c);
    EXPECT_LT((a.ring_key - b.ring_key).norm(), 0.1) << yaw;
    const PlaceComparison cmp = ComparePlaces(b, a);
    EXPECT_LT(cmp.distance, 0.2) << yaw;
    EXPECT_NEAR(std::remainder(cmp.yaw_rad - yaw, 2 * M_PI), 0.0, 2 * M_PI / c.sectors) << yaw;
  }
}

TEST(PlaceDescriptor, AnotherPlaceIsFartherThanTheSamePlaceTurned) {
  const PlaceDescriptorConfig c;
  const PlaceDescriptor room = DescribePlace(Room(), c);
  std::vector<Eigen::Vector2d> corridor;
  for (int k = 0; k < 400; ++k) {
    corridor.emplace_back(-10 + 0.05 * k, 1.2);
    corridor.emplace_back(-10 + 0.05 * k, -1.3);
  }
  const PlaceDescriptor other = DescribePlace(corridor, c);
  const PlaceDescriptor turned = DescribePlace(Rotated(Room(), 0.7), c);
  EXPECT_GT(ComparePlaces(other, room).distance, ComparePlaces(turned, room).distance + 0.2);
  EXPECT_EQ(ComparePlaces(DescribePlace({}, c), room).distance, 1.0);  // nothing seen
}

TEST(PlaceIndex, FindsTheNearestRingKeysAndForgetsRemovedNodes) {
  const PlaceDescriptorConfig c;
  PlaceIndex index;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-15.0, 15.0);
  for (NodeId id = 0; id < 50; ++id) {
    std::vector<Eigen::Vector2d> pts;
    for (int k = 0; k < 100 + 5 * id; ++k) pts.emplace_back(u(rng), u(rng));
    index.Add(id, DescribePlace(pts, c));
  }
  index.Add(100, DescribePlace(Room(), c));
  const PlaceDescriptor query = DescribePlace(Rotated(Room(), 1.0), c);
  std::vector<NodeId> nearest = index.Nearest(query, 3);
  ASSERT_EQ(nearest.size(), 3u);
  EXPECT_EQ(nearest.front(), 100);
  index.Remove(100);
  EXPECT_FALSE(index.Contains(100));
  nearest = index.Nearest(query, 3);
  EXPECT_EQ(std::count(nearest.begin(), nearest.end(), NodeId{100}), 0);
  EXPECT_EQ(index.size(), 50u);
  EXPECT_THROW(index.Add(7, DescribePlace(Room(), c)), std::logic_error);  // 7 is there
}

}  // namespace
}  // namespace lifelong::slam
