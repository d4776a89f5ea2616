#include "sim/geometry.hpp"

#include <gtest/gtest.h>

namespace lifelong::sim {
namespace {

TEST(Geometry, SegmentsCrossTouchAndMiss) {
  EXPECT_TRUE(SegmentsIntersect({0, 0, 2, 2}, {0, 2, 2, 0}));   // X
  EXPECT_TRUE(SegmentsIntersect({0, 0, 1, 0}, {1, 0, 1, 1}));   // shared end
  EXPECT_FALSE(SegmentsIntersect({0, 0, 1, 0}, {0, 1, 1, 1}));  // parallel
  EXPECT_FALSE(SegmentsIntersect({0, 0, 1, 0}, {2, 0, 3, 0}));  // collinear, apart
}

TEST(Geometry, Distances) {
  EXPECT_DOUBLE_EQ(PointSegmentDistance({1, 1}, {0, 0, 2, 0}), 1.0);
  EXPECT_DOUBLE_EQ(PointSegmentDistance({3, 4}, {0, 0, -1, 0}), 5.0);  // to the end point
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance({0, 0, 1, 0}, {0, 2, 1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(SegmentSegmentDistance({0, 0, 2, 2}, {0, 2, 2, 0}), 0.0);
}

TEST(Geometry, PolygonInsideAndSelfIntersection) {
  const std::vector<Point> square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_TRUE(PointInPolygon({1, 1}, square));
  EXPECT_FALSE(PointInPolygon({3, 1}, square));
  EXPECT_FALSE(PolygonSelfIntersects(square));
  const std::vector<Point> bowtie{{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  EXPECT_TRUE(PolygonSelfIntersects(bowtie));
  EXPECT_EQ(ToSegments(square, true).size(), 4u);
  EXPECT_EQ(ToSegments(square, false).size(), 3u);
}

}  // namespace
}  // namespace lifelong::sim
