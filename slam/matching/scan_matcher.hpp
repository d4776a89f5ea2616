// Correlative multi-resolution scan matching (Olson 2009, "Real-time correlative scan
// matching", ICRA). Steps:
//  1. The reference points are rasterized into a likelihood field (lookup table): each cell
//     holds v = exp(-d^2 / (2 sigma^2)) of the distance d to the nearest reference point
//     (0 beyond 3 sigma), and ln v (floored at -4.5) for the pose probability.
//  2. Coarser tables (levels l = 1..log2 f, f = coarse factor) hold, at each fine cell c, the
//     max of v over [c, c + 2^l)^2, so one lookup bounds the score of 2^l x 2^l fine
//     translations (§III-B, with intermediate levels as in Cartographer's fast matcher).
//  3. For every rotation in the angular window, f x f blocks of translations get a bound and
//     are searched best bound first, each split into four children one level finer, a branch
//     being cut when its bound does not beat the best score found (branch and bound).
//     score = mean v over the query points, in [0, 1].
//  4. Ambiguity: the search continues for the best pose farther than ambiguity_radius_m (or
//     ambiguity_angle_rad) from the winner; ambiguity = its score / the best score.
//  5. Covariance (§III-C): with p_i = exp(sum_points ln v) of every evaluated fine pose,
//     Sigma = sum p_i (x_i - x*)(x_i - x*)^T / sum p_i, plus the pose grid's quantization
//     variance and a floor; information = Sigma^-1.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "slam/grid/scratch_table.hpp"

namespace lifelong::slam {

struct MatcherConfig {
  double linear_window_m = 0.3;      ///< m, half-width of the search in x and in y
  double angular_window_rad = 0.26;  ///< rad, half-width of the search in heading
  double resolution_m = 0.03;        ///< m, fine lookup-table cell = translation step
  double angular_step_rad = 0.0;     ///< rad; 0: resolution / (max point range, 1..10 m)
  int coarse_factor = 16;            ///< fine cells per top-level block side, a power of 2
  double sigma_m = 0.05;             ///< m, Gaussian sigma of the likelihood field
  double min_score = 0.5;            ///< a match with a lower score is not ok
  double ambiguity_radius_m = 0.5;   ///< m, competitors are at least this far away...
  double ambiguity_angle_rad = 0.2;  ///< rad, ...or at least this far in heading
  double floor_sigma_m = 0.01;       ///< m, added in quadrature to the x and y sigmas
  double floor_sigma_rad = 0.005;    ///< rad, added in quadrature to the heading sigma
  /// Refine the lattice winner off the lattice (scan_refiner.hpp): within one translation
  /// cell and one angular step, by damped ascent on the bicubically interpolated field.
  bool refine = true;
  /// A first branch and bound starts from min_score rather than from nothing, as
  /// Cartographer's fast matcher starts from its minimum score (Hess et al. 2016, §V-C,
  /// Algorithm 3): a block whose bound does not beat min_score is never opened. Where it finds
  /// no pose, the match is not ok and its score unknown (NaN), at a fraction of the cost;
  /// where it finds one, the full search follows, and the result is the full search's to the
  /// bit (pose, score, ambiguity, covariance). false: every search is the full one. Set by
  /// the loop closer (loops.measure_low_scores), not by a config file.
  bool cut_below_min_score = false;
};

/// What one search with this config allocates whatever the scan: the lookup tables over the
/// translation window (the fine table, its log table and a bound table per coarse level, 4
/// bytes a cell; the scan's own extent adds to this) and the branch-and-bound frontier (every
/// rotation times every top-level block, 16 bytes a node; an automatic angular step is taken
/// at its finest, resolution / 10 m).
struct MatcherFootprint {
  double table_bytes = 0.0;
  double frontier_bytes = 0.0;
};
MatcherFootprint EstimateFootprint(const MatcherConfig& config, double linear_window_m,
                                   double angular_window_rad);
/// Settings whose footprint passes this are refused when loaded (2 GiB each).
inline constexpr double kMaxMatcherBytes = 2147483648.0;

/// Likelihood field of a reference point set, in the reference frame (steps 1 and 2).
class ReferenceGrid {
 public:
  /// An empty table (every lookup is 0), to be filled by Build.
  ReferenceGrid() = default;
  /// Only resolution_m, sigma_m and coarse_factor of the config are used here.
  ReferenceGrid(const std::vector<Eigen::Vector2d>& points_in_ref, const MatcherConfig& config);
  /// Rebuilds the tables for other points, reusing their memory: a mapper builds one per
  /// scan, and fresh multi-megabyte tables cost more in page faults than in filling them.
  void Build(const std::vector<Eigen::Vector2d>& points_in_ref, const MatcherConfig& config);

  double resolution_m() const { return resolution_m_; }
  int coarse_factor() const { return coarse_factor_; }
  int width() const { return width_; }
  int height() const { return height_; }
  /// Cell containing a reference-frame point, unclamped.
  Eigen::Vector2i CellOf(const Eigen::Vector2d& p) const;
  bool Contains(int x, int y) const { return x >= 0 && y >= 0 && x < width_ && y < height_; }
  /// Likelihood v in [0, 1]; 0 outside the table.
  float Likelihood(int x, int y) const { return Contains(x, y) ? levels_[0][Index(x, y)] : 0.0f; }
  /// ln v, floored; the floor outside the table.
  float LogLikelihood(int x, int y) const;
  /// v at a reference-frame point, bicubic (Catmull-Rom) between the cell centres (0 outside the
  /// table), with its gradient in 1/m when `gradient` is not null.
  double Interpolate(const Eigen::Vector2d& p, Eigen::Vector2d* gradient) const;
  /// Number of tables: level 0 is Likelihood, level l the max over 2^l x 2^l cells.
  int num_levels() const { return num_levels_; }
  /// Builds the coarse levels 1..top_level where a search can read them: on the tiles
  /// (coarse_factor x coarse_factor cells) within `reach` cells of any of `cells` (the query
  /// cells at every rotation; a search reads level l at c + (i, j), |i|, |j| <= reach), and
  /// below them on what each of those reads. A wide hall's table is mostly free space that no
  /// search looks at: building every level over it was 37 % of a real log's replay. Tiles
  /// built since the last Build are kept. The lazily built levels are a cache behind a const
  /// interface, so a grid must not be searched from two threads at once.
  void PrepareBounds(const std::vector<std::vector<Eigen::Vector2i>>& cells, int reach,
                     int top_level) const;
  /// Every coarse level on every tile.
  void PrepareAllBounds() const;
  /// Max of Likelihood over [x, x + 2^level) x [y, y + 2^level); 0 outside the table. Valid
  /// where PrepareBounds or PrepareAllBounds built the level.
  float Bound(int level, int x, int y) const {
    return Contains(x, y) ? levels_[static_cast<std::size_t>(level)][Index(x, y)] : 0.0f;
  }
  /// Level `level`'s table, row-major (width() x height()): Bound without the bounds check,
  /// for callers that know their cells lie inside (and were prepared).
  const float* BoundTable(int level) const {
    return levels_[static_cast<std::size_t>(level)].data();
  }

  static constexpr float kLogFloor = -4.5f;

 private:
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(x);
  }
  void Rasterize(const std::vector<Eigen::Vector2d>& points, double sigma_m);
  /// Sizes the coarse levels, none of their tiles built (reference_grid_levels.cpp).
  void ResetLevels();
  /// Builds level `level` (>= 1) on the tiles whose bit `level` is set in `need` (per tile),
  /// from level - 1, unless built since the last Build.
  void BuildTiles(int level, const std::vector<std::uint32_t>& need) const;
  void BuildTile(int level, int tx, int ty) const;

  double resolution_m_ = 1.0;
  int coarse_factor_ = 1;
  Eigen::Vector2d origin_m_ = Eigen::Vector2d::Zero();  ///< lower-left corner of cell (0, 0)
  int width_ = 0;
  int height_ = 0;
  int num_levels_ = 1;
  /// levels_[0]: v per cell, every cell written by Build; levels 1.. are built tile by tile
  /// (PrepareBounds), so never zeroed by a resize (scratch_table.hpp). Levels past
  /// num_levels_ are spare capacity.
  using Table = std::vector<float, UninitializedAllocator<float>>;
  mutable std::vector<Table> levels_ = {{}};
  int tile_ = 1;                                   ///< cells per tile side: coarse_factor_
  int tiles_x_ = 0, tiles_y_ = 0;                  ///< tiles across and up the table
  mutable std::vector<std::uint32_t> tile_ready_;  ///< per tile, bit l: level l built there
};

struct MatchResult {
  Pose2 T_ref_cur;  ///< best pose of the current frame in the reference
  /// Mean likelihood of the query points, 0..1; NaN when cut_below_min_score found no pose
  /// at min_score or above.
  double score = 0.0;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();   ///< (x, y, theta)
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  ///< covariance^-1
  bool ok = false;                                            ///< score >= min_score
  double ambiguity = 0.0;  ///< best distinct competitor's score / score; 0 if none (NaN as score)
  Pose2 T_ref_rival;       ///< that competitor's pose (lattice), when ambiguity > 0
  int evaluations = 0;     ///< fine poses scored
  int bound_evaluations = 0;  ///< coarser bounds computed
};

/// Matches points (current robot frame) against the reference around the guess.
MatchResult Match(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points_in_cur,
                  const Pose2& T_ref_cur_guess, const MatcherConfig& config);

/// Match's score of one pose, without a search: the mean likelihood of the points placed at
/// T_ref_cur (each looked up in the fine cell it falls in).
double ScoreAt(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points_in_cur,
               const Pose2& T_ref_cur);

/// Keeps the reference points that can change the match of `points_in_cur` around the
/// guess: those whose likelihood kernel reaches a table cell that Match would look up for some
/// rotation and translation of its search lattice (its bounds' blocks included). The match is
/// unchanged; the table built from the rest is smaller and faster to build.
void CropToSearch(const std::vector<Eigen::Vector2d>& points_in_cur, const Pose2& T_ref_cur_guess,
                  const MatcherConfig& config, std::vector<Eigen::Vector2d>* reference);

/// End points of the returns of a scan in the robot frame (via T_robot_laser), thinned so
/// that at most one point falls in each spacing_m x spacing_m voxel (the first one kept).
std::vector<Eigen::Vector2d> ScanToPoints(const LaserScan& scan, double spacing_m);
/// Which consecutive returns of a scan SurfacePoints joins into a surface. The defaults are
/// the mapper's (IncrementalConfig::surfaces).
struct SurfaceRule {
  /// Two consecutive returns less than this apart are joined, whatever the shape around them.
  double gap_m = 0.3;
  /// Two consecutive returns up to this far apart are joined when the segment lies on one line
  /// with the segments on either side: the four returns within line_tol_m of their fitted line
  /// and in beam order along it. A wall hit at a grazing angle passes (its returns spread out
  /// along it); a depth jump, whose segment runs along the beams from one surface to another
  /// behind it, does not. 0: off (before 2026-12-02).
  double line_gap_m = 1.5;
  double line_tol_m = 0.02;
  /// Whether any returns are joined (else SurfacePoints gives the return points alone).
  bool JoinsAny() const { return gap_m > 0.0 || line_gap_m > 0.0; }
};

/// The scan's surfaces in the robot frame: its return end points and points every
/// spacing_m / 2 along each segment joining two consecutive returns that `rule` joins, thinned
/// to one per spacing_m voxel (spacing_m > 0).
std::vector<Eigen::Vector2d> SurfacePoints(const LaserScan& scan, double spacing_m,
                                           const SurfaceRule& rule);

/// A scan placed at a pose in the reference frame.
struct PosedScan {
  const LaserScan* scan = nullptr;
  Pose2 T_ref_robot;
};

/// Return end points of several scans in the reference frame, voxel-thinned together.
std::vector<Eigen::Vector2d> PointsInReference(const std::vector<PosedScan>& scans,
                                               double spacing_m);

}  // namespace lifelong::slam
