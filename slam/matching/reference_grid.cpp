// Likelihood-field lookup tables and scan point extraction for the correlative matcher
// (Olson 2009, §III-A/B); see scan_matcher.hpp.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_set>

#include <Eigen/Eigenvalues>

#include "slam/grid/scratch_table.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {

namespace {

// The spacing_m voxel of p, as one key.
std::uint64_t VoxelKey(const Eigen::Vector2d& p, double spacing_m) {
  const auto vx = static_cast<std::int32_t>(std::floor(p.x() / spacing_m));
  const auto vy = static_cast<std::int32_t>(std::floor(p.y() / spacing_m));
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(vx)) << 32) |
         static_cast<std::uint32_t>(vy);
}

// The end point of beam i (a return) in the frame T_frame_laser maps the laser frame into.
Eigen::Vector2d ReturnPoint(const LaserScan& scan, std::size_t i, const Pose2& T_frame_laser) {
  const double r = scan.ranges_m[i], a = scan.Bearing(i);
  Eigen::Vector2d p;
  T_frame_laser.Apply(r * std::cos(a), r * std::sin(a), &p.x(), &p.y());
  return p;
}

// Appends the return end points of `scan` seen from T_frame_robot, keeping the first point
// of each spacing_m voxel (voxels shared through `seen`).
void AppendPoints(const LaserScan& scan, const Pose2& T_frame_robot, double spacing_m,
                  std::unordered_set<std::uint64_t>* seen, std::vector<Eigen::Vector2d>* out) {
  const Pose2 T_frame_laser = T_frame_robot * scan.T_robot_laser;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!scan.IsReturn(i)) continue;
    const Eigen::Vector2d p = ReturnPoint(scan, i, T_frame_laser);
    if (spacing_m > 0.0 && !seen->insert(VoxelKey(p, spacing_m)).second) continue;
    out->push_back(p);
  }
}

// Beams sweeping along a wall spread their returns out gradually: at 1 degree per beam, the
// step between returns grows by less than 1.8 times from one beam to the next as long as the
// beams meet the wall at 4 degrees or more. A step many times its neighbours' is a jump.
constexpr double kMaxStepGrowth = 3.0;

// Whether b-c, the step between consecutive returns a, b, c, d, continues a surface: the four lie
// within tol_m of their least-squares line, in this order along it, and b-c is at most
// kMaxStepGrowth times a-b and c-d.
bool OnOneLine(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
               const Eigen::Vector2d& d, double tol_m) {
  const double step = (c - b).norm();
  if (step > kMaxStepGrowth * (b - a).norm() || step > kMaxStepGrowth * (d - c).norm()) {
    return false;
  }
  const Eigen::Vector2d mean = 0.25 * (a + b + c + d);
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d* p : {&a, &b, &c, &d})
    scatter += (*p - mean) * (*p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  const Eigen::Vector2d along = eig.eigenvectors().col(1), across = eig.eigenvectors().col(0);
  double last = -std::numeric_limits<double>::infinity();
  const double sign = along.dot(d - a) >= 0.0 ? 1.0 : -1.0;
  for (const Eigen::Vector2d* p : {&a, &b, &c, &d}) {
    if (std::abs(across.dot(*p - mean)) > tol_m) return false;
    const double t = sign * along.dot(*p - mean);
    if (!(t > last)) return false;
    last = t;
  }
  return true;
}

}  // namespace

std::vector<Eigen::Vector2d> SurfacePoints(const LaserScan& scan, double spacing_m,
                                           const SurfaceRule& rule) {
  if (!(spacing_m > 0.0)) throw std::invalid_argument("SurfacePoints: spacing_m must be > 0");
  // The returns, with a break (nullopt) at every beam without one.
  std::vector<std::optional<Eigen::Vector2d>> beams(scan.ranges_m.size());
  for (std::size_t i = 0; i < beams.size(); ++i) {
    if (scan.IsReturn(i)) beams[i] = ReturnPoint(scan, i, scan.T_robot_laser);
  }
  const auto joined = [&](std::size_t i) {  // beams i and i + 1
    const Eigen::Vector2d &p = *beams[i], &q = *beams[i + 1];
    const double gap = (q - p).norm();
    if (gap < rule.gap_m) return true;
    if (!(gap < rule.line_gap_m) || i == 0 || i + 2 >= beams.size()) return false;
    return beams[i - 1] && beams[i + 2] &&
           OnOneLine(*beams[i - 1], p, q, *beams[i + 2], rule.line_tol_m);
  };
  std::unordered_set<std::uint64_t> seen;
  std::vector<Eigen::Vector2d> out;
  const auto keep = [&](const Eigen::Vector2d& p) {
    if (seen.insert(VoxelKey(p, spacing_m)).second) out.push_back(p);
  };
  for (std::size_t i = 0; i < beams.size(); ++i) {
    if (!beams[i]) continue;
    keep(*beams[i]);
    if (i + 1 >= beams.size() || !beams[i + 1] || !joined(i)) continue;
    const Eigen::Vector2d &p = *beams[i], &q = *beams[i + 1];
    const int n = static_cast<int>(std::ceil((q - p).norm() / (0.5 * spacing_m)));
    for (int k = 1; k < n; ++k) keep(p + (q - p) * (static_cast<double>(k) / n));
  }
  return out;
}

std::vector<Eigen::Vector2d> ScanToPoints(const LaserScan& scan, double spacing_m) {
  return PointsInReference({PosedScan{&scan, Pose2()}}, spacing_m);
}

std::vector<Eigen::Vector2d> PointsInReference(const std::vector<PosedScan>& scans,
                                               double spacing_m) {
  std::unordered_set<std::uint64_t> seen;
  std::vector<Eigen::Vector2d> out;
  for (const PosedScan& s : scans) AppendPoints(*s.scan, s.T_ref_robot, spacing_m, &seen, &out);
  return out;
}

ReferenceGrid::ReferenceGrid(const std::vector<Eigen::Vector2d>& points_in_ref,
                             const MatcherConfig& config) {
  Build(points_in_ref, config);
}

void ReferenceGrid::Build(const std::vector<Eigen::Vector2d>& points_in_ref,
                          const MatcherConfig& config) {
  if (!(config.resolution_m > 0.0) || !(config.sigma_m > 0.0)) {
    throw std::invalid_argument("ReferenceGrid: resolution_m and sigma_m must be > 0");
  }
  resolution_m_ = config.resolution_m;
  coarse_factor_ = 1;
  while (coarse_factor_ < config.coarse_factor) coarse_factor_ *= 2;
  Rasterize(points_in_ref, config.sigma_m);
  ResetLevels();
}

// Computed at each lookup rather than tabled: a match reads a few thousand cells (its points
// at the poses it evaluates), a table cost a log pass over every cell of the grid.
float ReferenceGrid::LogLikelihood(int x, int y) const {
  if (!Contains(x, y)) return kLogFloor;
  const float v = levels_[0][Index(x, y)];
  return v > 0.0f ? std::max(std::log(v), kLogFloor) : kLogFloor;
}

namespace {
/// Catmull-Rom weights (cubic convolution, a = -0.5) of the samples at -1, 0, 1, 2 for t in
/// [0, 1), and their derivatives: C1 between samples, exact on quadratics.
void CubicWeights(double t, double w[4], double dw[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
  w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
  w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
  dw[0] = 0.5 * (-3.0 * t2 + 4.0 * t - 1.0);
  dw[1] = 0.5 * (9.0 * t2 - 10.0 * t);
  dw[2] = 0.5 * (-9.0 * t2 + 8.0 * t + 1.0);
  dw[3] = 0.5 * (3.0 * t2 - 2.0 * t);
}
}  // namespace

double ReferenceGrid::Interpolate(const Eigen::Vector2d& p, Eigen::Vector2d* gradient) const {
  // Cell (i, j) holds v at its centre, origin + (i + 0.5, j + 0.5) r; bicubic (Catmull-Rom)
  // over the 4 x 4 centres around p, as Cartographer's Ceres matcher interpolates its grid.
  const Eigen::Vector2d u = (p - origin_m_) / resolution_m_ - Eigen::Vector2d::Constant(0.5);
  const int i = static_cast<int>(std::floor(u.x())), j = static_cast<int>(std::floor(u.y()));
  double wx[4], dwx[4], wy[4], dwy[4];
  CubicWeights(u.x() - i, wx, dwx);
  CubicWeights(u.y() - j, wy, dwy);
  double v = 0.0, gx = 0.0, gy = 0.0;
  for (int b = 0; b < 4; ++b) {
    double row = 0.0, drow = 0.0;
    for (int a = 0; a < 4; ++a) {
      const double s = Likelihood(i - 1 + a, j - 1 + b);
      row += wx[a] * s;
      drow += dwx[a] * s;
    }
    v += wy[b] * row;
    gx += wy[b] * drow;
    gy += dwy[b] * row;
  }
  if (gradient != nullptr) *gradient = Eigen::Vector2d(gx, gy) / resolution_m_;
  return v;
}

Eigen::Vector2i ReferenceGrid::CellOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d c = (p - origin_m_) / resolution_m_;
  return {static_cast<int>(std::floor(c.x())), static_cast<int>(std::floor(c.y()))};
}

// Step 1: v = exp(-d^2 / (2 sigma^2)) of the nearest point within 3 sigma, at cell centres.
void ReferenceGrid::Rasterize(const std::vector<Eigen::Vector2d>& points, double sigma_m) {
  width_ = height_ = 0;
  if (points.empty()) {
    levels_[0].clear();
    return;
  }
  Eigen::Vector2d lo = points.front(), hi = points.front();
  for (const Eigen::Vector2d& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double r = resolution_m_;
  const int kernel = static_cast<int>(std::ceil(3.0 * sigma_m / r));
  const int margin = kernel + coarse_factor_ + 1;
  origin_m_ = (lo / r).array().floor().matrix() * r - Eigen::Vector2d::Constant(margin * r);
  width_ = static_cast<int>(std::ceil((hi.x() - origin_m_.x()) / r)) + margin + 1;
  height_ = static_cast<int>(std::ceil((hi.y() - origin_m_.y()) / r)) + margin + 1;
  Table& fine = levels_[0];
  ResizeTable(&fine, static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
  std::fill(fine.begin(), fine.end(), 0.0f);
  const double max_d2 = 9.0 * sigma_m * sigma_m, inv_2s2 = 1.0 / (2.0 * sigma_m * sigma_m);
  // The Gaussian is separable: exp(-(dx^2 + dy^2) / 2s^2) = gx(dx) * gy(dy), so each point
  // costs 2 (2k + 1) exponentials instead of (2k + 1)^2.
  const std::size_t span = static_cast<std::size_t>(2 * kernel + 1);
  std::vector<double> gx(span), gy(span), dx2(span), dy2(span);
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2i c = CellOf(p);
    for (int i = -kernel; i <= kernel; ++i) {
      const auto k = static_cast<std::size_t>(i + kernel);
      const double cx = origin_m_.x() + (c.x() + i + 0.5) * r - p.x();
      const double cy = origin_m_.y() + (c.y() + i + 0.5) * r - p.y();
      dx2[k] = cx * cx;
      dy2[k] = cy * cy;
      gx[k] = std::exp(-dx2[k] * inv_2s2);
      gy[k] = std::exp(-dy2[k] * inv_2s2);
    }
    for (int j = -kernel; j <= kernel; ++j) {
      const auto kj = static_cast<std::size_t>(j + kernel);
      for (int i = -kernel; i <= kernel; ++i) {
        const auto ki = static_cast<std::size_t>(i + kernel);
        if (dx2[ki] + dy2[kj] > max_d2) continue;
        float& v = fine[Index(c.x() + i, c.y() + j)];
        v = std::max(v, static_cast<float>(gx[ki] * gy[kj]));
      }
    }
  }
}

}  // namespace lifelong::slam
