// What the mapper holds of each graph node: its scan, the thinned points the matchers use,
// and where the map renders it. One definition, read by the mapper, the loop closer and
// pruning.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include <Eigen/Core>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"
#include "slam/grid/grid_map.hpp"
#include "slam/matching/incremental_config.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {

struct NodeData {
  LaserScan scan;
  std::vector<Eigen::Vector2d> points;  ///< thinned return end points, robot frame
  Pose2 T_world_map;                    ///< pose at which the scan is rendered in the map
  Pose2 T_odom_robot;                   ///< odometry at the scan
  int scan_index = 0;
  double travelled_m = 0.0;  ///< robot path length (odometry) at this scan
  /// Beams of `scan` a removal policy found outdated (SampleRetirement), ascending by beam:
  /// the map traces them cut (GridMap::TouchedCells).
  std::vector<BeamCut> cuts;
};

/// The graph's nodes by id.
using NodeStore = std::map<NodeId, NodeData>;

/// A scan's surfaces in the robot frame, by `rule` (SurfacePoints), sampled at the
/// incremental matcher's thinning spacing (its likelihood field's resolution without
/// thinning).
std::vector<Eigen::Vector2d> ScanSurfaces(const LaserScan& scan, const IncrementalConfig& inc,
                                          const SurfaceRule& rule);

/// Points of the robot frame in the world frame of pose T.
std::vector<Eigen::Vector2d> ToWorld(const std::vector<Eigen::Vector2d>& points, const Pose2& T);

/// Rotates a world-frame (x, y, theta) covariance or information into the frame of a pose
/// with heading theta_rad: R^T M R on the translation block.
Eigen::Matrix3d RotateIntoFrame(const Eigen::Matrix3d& m, double theta_rad);

}  // namespace lifelong::slam
