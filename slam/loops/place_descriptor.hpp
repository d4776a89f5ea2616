// A place descriptor for global loop closing: Scan Context (Kim and Kim 2018, "Scan Context:
// Egocentric Spatial Descriptor for Place Recognition within 3D Point Cloud Map", IROS), in
// 2D. The points around a node (its scan and its recent neighbours', in its frame) fall into
// a polar grid of `rings` x `sectors` bins out to max_range_m; a bin is 1 when it holds a
// point. Two descriptors are compared column-wise (a column is a sector): the mean cosine
// distance of the non-empty column pairs, minimised over circular column shifts, which also
// gives the heading of one place in the other (Kim and Kim eqs. 5-6). The ring key, the
// share of occupied bins per ring, does not change with heading and indexes the places
// (eq. 7).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace lifelong::slam {

struct PlaceDescriptorConfig {
  int rings = 20;             ///< radial bins
  int sectors = 60;           ///< angular bins (6 deg each)
  double max_range_m = 20.0;  ///< m, points farther out are left out
};

struct PlaceDescriptor {
  Eigen::MatrixXf bins;      ///< rings x sectors, 0 or 1; sector 0 starts at heading -pi
  Eigen::VectorXf ring_key;  ///< per ring, the share of its sectors that hold a point
  int occupied = 0;          ///< bins holding a point
};

/// The descriptor of the points, given in the place's own frame (x ahead).
PlaceDescriptor DescribePlace(const std::vector<Eigen::Vector2d>& points_in_place,
                              const PlaceDescriptorConfig& config);

struct PlaceComparison {
  double distance = 1.0;  ///< in [0, 1]: 0 the same columns, 1 nothing in common
  double yaw_rad = 0.0;   ///< heading of the query's frame in the candidate's, at the best shift
};

/// Compares a query with a candidate of the same configuration (eqs. 5-6). Empty descriptors
/// are 1 apart.
PlaceComparison ComparePlaces(const PlaceDescriptor& query, const PlaceDescriptor& candidate);

}  // namespace lifelong::slam
