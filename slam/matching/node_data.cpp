#include "slam/matching/node_data.hpp"

#include <cmath>

namespace lifelong::slam {

std::vector<Eigen::Vector2d> ScanSurfaces(const LaserScan& scan, const IncrementalConfig& inc,
                                          const SurfaceRule& rule) {
  const double spacing = inc.point_spacing_m > 0.0 ? inc.point_spacing_m : inc.matcher.resolution_m;
  return SurfacePoints(scan, spacing, rule);
}

std::vector<Eigen::Vector2d> ToWorld(const std::vector<Eigen::Vector2d>& points, const Pose2& T) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    double x = 0.0, y = 0.0;
    T.Apply(p.x(), p.y(), &x, &y);
    out.emplace_back(x, y);
  }
  return out;
}

Eigen::Matrix3d RotateIntoFrame(const Eigen::Matrix3d& m, double theta_rad) {
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  T.block<2, 2>(0, 0) << c, s, -s, c;  // R^T
  return T * m * T.transpose();
}

}  // namespace lifelong::slam
