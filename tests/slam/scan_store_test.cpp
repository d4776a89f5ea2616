// ScanStore: scans follow the node that anchors them, pending scans go to the nearer node by
// odometry, and a removed node hands its scans on without moving them.
#include "slam/mapping/scan_store.hpp"

#include <gtest/gtest.h>

namespace lifelong::slam {
namespace {

void ExpectPose(const Pose2& a, const Pose2& b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.theta, b.theta, 1e-12);
}

TEST(ScanStore, PendingScansGoToTheNearerNodeAndFollowIt) {
  ScanStore store;
  EXPECT_EQ(store.AddNodeScan(0.0, 0, Pose2(0.0, 0.0, 0.0)), 0u);
  store.AddPending(0.1, 0, Pose2(0.2, 0.0, 0.0), Pose2(0.2, 0.0, 0.0));  // nearer node 0
  store.AddPending(0.2, 0, Pose2(0.8, 0.0, 0.0), Pose2(0.8, 0.0, 0.0));  // nearer node 1
  store.AnchorPending(0, 1, Pose2(1.0, 0.0, 0.0));
  EXPECT_EQ(store.AddNodeScan(0.3, 1, Pose2(1.0, 0.0, 0.0)), 3u);
  // The estimate moves node 1 up by 1 m: only the scans it holds move with it.
  const Values values{{0, Pose2(0.0, 0.0, 0.0)}, {1, Pose2(1.0, 1.0, 0.0)}};
  const std::vector<StampedPose> t = store.Trajectory(values);
  ASSERT_EQ(t.size(), 4u);
  ExpectPose(t[1].T_world_robot, Pose2(0.2, 0.0, 0.0));
  ExpectPose(t[2].T_world_robot, Pose2(0.8, 1.0, 0.0));
  ExpectPose(t[3].T_world_robot, Pose2(1.0, 1.0, 0.0));
  EXPECT_DOUBLE_EQ(store.stamp(2), 0.2);
  EXPECT_DOUBLE_EQ(store.Last(values).stamp_s, 0.3);
}

TEST(ScanStore, AMeasuredPendingScanStaysWithItsNode) {
  ScanStore store;
  store.AddNodeScan(0.0, 0, Pose2());
  // Nearer node 1 by odometry, but measured against node 0: it stays there.
  store.AddPending(0.1, 0, Pose2(0.75, 0.05, 0.0), Pose2(0.8, 0.0, 0.0), true);
  store.AnchorPending(0, 1, Pose2(1.0, 0.0, 0.0));
  store.AddNodeScan(0.2, 1, Pose2(1.0, 0.0, 0.0));
  const Values values{{0, Pose2(0.0, 0.0, 0.0)}, {1, Pose2(1.0, 1.0, 0.0)}};
  ExpectPose(store.Trajectory(values)[1].T_world_robot, Pose2(0.75, 0.05, 0.0));
}

TEST(ScanStore, ARemovedNodeHandsItsScansOnInPlace) {
  ScanStore store;
  store.AddNodeScan(0.0, 0, Pose2());
  store.AddNodeScan(1.0, 1, Pose2(1.0, 0.0, 0.0));
  store.AddPending(1.5, 1, Pose2(0.5, 0.0, 0.0), Pose2(1.5, 0.0, 0.0));
  store.AddNodeScan(2.0, 2, Pose2(2.0, 0.0, 0.0));
  const Values before{{0, Pose2()}, {1, Pose2(1.0, 0.0, 0.5)}, {2, Pose2(2.0, 0.0, 0.0)}};
  const std::vector<StampedPose> expected = store.Trajectory(before);
  store.Handover(1, 2, Between(before.at(2), before.at(1)));
  const Values after{{0, Pose2()}, {2, Pose2(2.0, 0.0, 0.0)}};  // node 1 is gone
  const std::vector<StampedPose> moved = store.Trajectory(after);
  ASSERT_EQ(moved.size(), expected.size());
  for (std::size_t i = 0; i < moved.size(); ++i) {
    ExpectPose(moved[i].T_world_robot, expected[i].T_world_robot);
  }
}

}  // namespace
}  // namespace lifelong::slam
