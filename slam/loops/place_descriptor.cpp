#include "slam/loops/place_descriptor.hpp"

#include <algorithm>
#include <cmath>

namespace lifelong::slam {

PlaceDescriptor DescribePlace(const std::vector<Eigen::Vector2d>& points,
                              const PlaceDescriptorConfig& c) {
  PlaceDescriptor d;
  d.bins = Eigen::MatrixXf::Zero(c.rings, c.sectors);
  for (const Eigen::Vector2d& p : points) {
    const double r = p.norm();
    if (!(r < c.max_range_m)) continue;
    const int ring = std::min(c.rings - 1, static_cast<int>(r / c.max_range_m * c.rings));
    const double a = std::atan2(p.y(), p.x()) + M_PI;  // [0, 2 pi]
    const int sector = std::min(c.sectors - 1, static_cast<int>(a / (2.0 * M_PI) * c.sectors));
    d.bins(ring, sector) = 1.0f;
  }
  d.ring_key = d.bins.rowwise().mean();
  d.occupied = static_cast<int>(d.bins.sum());
  return d;
}

PlaceComparison ComparePlaces(const PlaceDescriptor& q, const PlaceDescriptor& c) {
  PlaceComparison best;
  if (q.occupied == 0 || c.occupied == 0 || q.bins.cols() != c.bins.cols() ||
      q.bins.rows() != c.bins.rows()) {
    return best;
  }
  const int n = static_cast<int>(q.bins.cols());
  const Eigen::RowVectorXf qn = q.bins.colwise().norm(), cn = c.bins.colwise().norm();
  // A shift that overlaps a few columns would match by chance (a 180 deg laser leaves half
  // the columns empty): at least half of the sparser descriptor's columns must pair up.
  const int q_cols = static_cast<int>((qn.array() > 0.0f).count());
  const int c_cols = static_cast<int>((cn.array() > 0.0f).count());
  const int min_pairs = std::max(3, std::min(q_cols, c_cols) / 2);
  for (int shift = 0; shift < n; ++shift) {
    // The query's sector j looks where the candidate's sector j + shift looks.
    double sum = 0.0;
    int pairs = 0;
    for (int j = 0; j < n; ++j) {
      const int k = (j + shift) % n;
      if (qn(j) == 0.0f || cn(k) == 0.0f) continue;
      sum += 1.0 - q.bins.col(j).dot(c.bins.col(k)) / (qn(j) * cn(k));
      ++pairs;
    }
    if (pairs < min_pairs) continue;
    const double distance = std::clamp(sum / pairs, 0.0, 1.0);  // rounding below 0
    if (distance < best.distance) {
      best.distance = distance;
      best.yaw_rad = 2.0 * M_PI * shift / n;
    }
  }
  best.yaw_rad = std::remainder(best.yaw_rad, 2.0 * M_PI);
  return best;
}

}  // namespace lifelong::slam
