// slam::SurfaceCache: each node's points made once while cached, at most `capacity` nodes,
// the least recently used going first.
#include "slam/loops/surface_cache.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace lifelong::slam {
namespace {

TEST(SurfaceCache, MakesEachNodesPointsOnceAndEvictsTheLeastRecentlyUsed) {
  SurfaceCache cache(2);
  int made = 0;
  const auto points_of = [&made](NodeId id) {
    return [&made, id] {
      ++made;
      return std::vector<Eigen::Vector2d>{Eigen::Vector2d(id, 0.0)};
    };
  };
  EXPECT_EQ(cache.Get(1, points_of(1)).front().x(), 1.0);
  EXPECT_EQ(cache.Get(2, points_of(2)).front().x(), 2.0);
  EXPECT_EQ(cache.Get(1, points_of(1)).front().x(), 1.0);  // a hit: 2 is now the oldest
  EXPECT_EQ(made, 2);
  EXPECT_EQ(cache.Get(3, points_of(3)).front().x(), 3.0);  // evicts 2, not 1
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_EQ(made, 3);
  cache.Get(1, points_of(1));
  EXPECT_EQ(made, 3);
  cache.Get(2, points_of(2));
  EXPECT_EQ(made, 4);
  EXPECT_EQ(cache.hits(), 2u);
  EXPECT_EQ(cache.misses(), 4u);
  cache.Erase(2);
  cache.Get(2, points_of(2));
  EXPECT_EQ(made, 5);
  EXPECT_LE(cache.size(), 2u);
}

}  // namespace
}  // namespace lifelong::slam
