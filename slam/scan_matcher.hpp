// Correlative multi-resolution scan matching (Olson 2009, "Real-time correlative scan
// matching", ICRA). Steps:
//  1. The reference points are rasterized into a likelihood field (lookup table): each cell
//     holds v = exp(-d^2 / (2 sigma^2)) of the distance d to the nearest reference point
//     (0 beyond 3 sigma), and ln v (floored at -4.5) for the pose probability.
//  2. A coarse table holds, at each fine cell c, the max of v over [c, c + f)^2 (f = coarse
//     factor), so one coarse lookup bounds the score of f x f fine translations (§III-B).
//  3. For every rotation in the angular window, each block of f x f translations gets a bound;
//     blocks are expanded best bound first until no bound beats the best fine score
//     (branch and bound). score = mean v over the query points, in [0, 1].
//  4. Ambiguity: the search continues for the best pose farther than ambiguity_radius_m (or
//     ambiguity_angle_rad) from the winner; ambiguity = its score / the best score.
//  5. Covariance (§III-C): with p_i = exp(sum_points ln v) of every evaluated fine pose,
//     Sigma = sum p_i (x_i - x*)(x_i - x*)^T / sum p_i, plus the pose grid's quantization
//     variance and a floor; information = Sigma^-1.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"

namespace lifelong::slam {

struct MatcherConfig {
  double linear_window_m = 0.3;      ///< m, half-width of the search in x and in y
  double angular_window_rad = 0.26;  ///< rad, half-width of the search in heading
  double resolution_m = 0.03;        ///< m, fine lookup-table cell = translation step
  double angular_step_rad = 0.0;     ///< rad; 0: resolution / (max point range, 1..10 m)
  int coarse_factor = 8;             ///< fine cells per coarse block side
  double sigma_m = 0.05;             ///< m, Gaussian sigma of the likelihood field
  double min_score = 0.5;            ///< a match with a lower score is not ok
  double ambiguity_radius_m = 0.5;   ///< m, competitors are at least this far away...
  double ambiguity_angle_rad = 0.2;  ///< rad, ...or at least this far in heading
  double floor_sigma_m = 0.01;       ///< m, added in quadrature to the x and y sigmas
  double floor_sigma_rad = 0.005;    ///< rad, added in quadrature to the heading sigma
};

/// Likelihood field of a reference point set, in the reference frame (steps 1 and 2).
class ReferenceGrid {
 public:
  /// Only resolution_m, sigma_m and coarse_factor of the config are used here.
  ReferenceGrid(const std::vector<Eigen::Vector2d>& points_in_ref, const MatcherConfig& config);

  double resolution_m() const { return resolution_m_; }
  int coarse_factor() const { return coarse_factor_; }
  int width() const { return width_; }
  int height() const { return height_; }
  /// Cell containing a reference-frame point, unclamped.
  Eigen::Vector2i CellOf(const Eigen::Vector2d& p) const;
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  /// Likelihood v in [0, 1]; 0 outside the table.
  float Likelihood(int x, int y) const { return Contains(x, y) ? fine_[Index(x, y)] : 0.0f; }
  /// ln v, floored; the floor outside the table.
  float LogLikelihood(int x, int y) const;
  /// Max of Likelihood over [x, x + f) x [y, y + f).
  float CoarseBound(int x, int y) const { return Contains(x, y) ? coarse_[Index(x, y)] : 0.0f; }

  static constexpr float kLogFloor = -4.5f;

 private:
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(x);
  }
  void Rasterize(const std::vector<Eigen::Vector2d>& points, double sigma_m);
  void BuildCoarse();

  double resolution_m_;
  int coarse_factor_;
  Eigen::Vector2d origin_m_ = Eigen::Vector2d::Zero();  ///< lower-left corner of cell (0, 0)
  int width_ = 0;
  int height_ = 0;
  std::vector<float> fine_;
  std::vector<float> log_fine_;
  std::vector<float> coarse_;
};

struct MatchResult {
  Pose2 T_ref_cur;     ///< best pose of the current frame in the reference
  double score = 0.0;  ///< mean likelihood of the query points, 0..1
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();   ///< (x, y, theta)
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  ///< covariance^-1
  bool ok = false;                                            ///< score >= min_score
  double ambiguity = 0.0;  ///< best distinct competitor's score / score; 0 if none
  int evaluations = 0;     ///< fine poses scored (coarse bounds not counted)
  int coarse_evaluations = 0;
};

/// Matches points (current robot frame) against the reference around the guess.
MatchResult Match(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points_in_cur,
                  const Pose2& T_ref_cur_guess, const MatcherConfig& config);

/// End points of the returns of a scan in the robot frame (via T_robot_laser), thinned so
/// that at most one point falls in each spacing_m x spacing_m voxel (the first one kept).
std::vector<Eigen::Vector2d> ScanToPoints(const LaserScan& scan, double spacing_m);

/// A scan placed at a pose in the reference frame.
struct PosedScan {
  const LaserScan* scan = nullptr;
  Pose2 T_ref_robot;
};

/// Return end points of several scans in the reference frame, voxel-thinned together.
std::vector<Eigen::Vector2d> PointsInReference(const std::vector<PosedScan>& scans,
                                               double spacing_m);

}  // namespace lifelong::slam
