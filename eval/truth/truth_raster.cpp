#include "eval/truth/truth_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace lifelong::eval {
namespace {

constexpr double kMarginM = 1.0;      // m around the truth's surfaces and trajectory
constexpr double kMarginCells = 4.0;  // at least: recall looks 1.5 cells beyond a wall

/// The lattice's cells as an 8-bit image, 255 everywhere but the segments' cells (0): the
/// convention cv::distanceTransform measures to.
cv::Mat DrawSegments(const Lattice& l, const std::vector<Segment>& segments) {
  cv::Mat img(l.rows, l.cols, CV_8UC1, cv::Scalar(255));
  for (const Segment& s : segments) {
    const LatticeCell a = l.CellOf(s.x0, s.y0), b = l.CellOf(s.x1, s.y1);
    cv::line(img, {a.col, a.row}, {b.col, b.row}, cv::Scalar(0), 1, cv::LINE_8);
  }
  return img;
}

/// Every cell's distance in cells to the nearest zero cell of `img`, row-major.
std::vector<float> DistanceTransform(const cv::Mat& img) {
  cv::Mat dist;
  cv::distanceTransform(img, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return std::vector<float>(dist.begin<float>(), dist.end<float>());
}

double PointSegmentDistance(double x, double y, const Segment& s) {
  const double dx = s.x1 - s.x0, dy = s.y1 - s.y0;
  const double len2 = dx * dx + dy * dy;
  const double t =
      len2 > 0.0 ? std::clamp(((x - s.x0) * dx + (y - s.y0) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(x - (s.x0 + t * dx), y - (s.y0 + t * dy));
}

/// The lattice as an occupancy grid: p = 1 on the cells `on_wall` takes, 0 elsewhere.
template <class OnWall>
OccupancyGrid GridOn(const Lattice& l, const OnWall& on_wall) {
  OccupancyGrid grid;
  grid.width = l.cols, grid.height = l.rows, grid.resolution_m = l.res;
  grid.origin_x_m = l.ox, grid.origin_y_m = l.oy;
  grid.p_occ.assign(l.size(), 0.0f);
  for (int row = 0; row < l.rows; ++row) {
    for (int col = 0; col < l.cols; ++col) {
      if (on_wall(LatticeCell{col, row})) grid.At(col, row) = 1.0f;
    }
  }
  return grid;
}

}  // namespace

LatticeCell Lattice::CellOf(double x, double y) const {
  return {static_cast<int>(std::floor((x - ox) / res + 1e-9)),
          static_cast<int>(std::floor((y - oy) / res + 1e-9))};
}

Lattice LatticeCovering(const std::vector<Segment>& segments,
                        const std::vector<std::pair<double, double>>& points, double res,
                        double margin_m) {
  double x0 = std::numeric_limits<double>::max(), y0 = x0;
  double x1 = std::numeric_limits<double>::lowest(), y1 = x1;
  const auto add = [&](double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  };
  for (const Segment& s : segments) add(s.x0, s.y0), add(s.x1, s.y1);
  for (const auto& [x, y] : points) add(x, y);
  if (x1 < x0) add(0.0, 0.0);
  Lattice l;
  l.res = res;
  l.ox = std::floor((x0 - margin_m) / res) * res;
  l.oy = std::floor((y0 - margin_m) / res) * res;
  l.cols = static_cast<int>(std::ceil((x1 + margin_m - l.ox) / res)) + 1;
  l.rows = static_cast<int>(std::ceil((y1 + margin_m - l.oy) / res)) + 1;
  return l;
}

std::vector<float> DistanceToCells(const Lattice& lattice,
                                   const std::vector<LatticeCell>& targets) {
  cv::Mat img(lattice.rows, lattice.cols, CV_8UC1, cv::Scalar(255));
  bool any = false;
  for (const LatticeCell& c : targets) {
    if (!lattice.Inside(c)) continue;
    img.at<uchar>(c.row, c.col) = 0;
    any = true;
  }
  return any ? DistanceTransform(img) : std::vector<float>{};
}

SegmentField::SegmentField(const Lattice& lattice, std::vector<Segment> segments)
    : lattice_(lattice), segments_(std::move(segments)) {
  if (segments_.empty()) return;
  distance_ = DistanceTransform(DrawSegments(lattice_, segments_));
}

double SegmentField::length_m() const {
  double len = 0.0;
  for (const Segment& s : segments_) len += std::hypot(s.x1 - s.x0, s.y1 - s.y0);
  return len;
}

double SegmentField::DistanceCells(const LatticeCell& c) const {
  if (segments_.empty()) return std::numeric_limits<double>::infinity();
  if (lattice_.Inside(c)) return distance_[lattice_.Index(c)];
  const double x = lattice_.CentreX(c.col), y = lattice_.CentreY(c.row);
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& s : segments_) best = std::min(best, PointSegmentDistance(x, y, s));
  return best / lattice_.res;
}

TruthRaster::TruthRaster(const GroundTruth& truth, const std::vector<Pose2>& true_trajectory,
                         double resolution_m) {
  std::vector<std::pair<double, double>> path;
  for (const Pose2& p : true_trajectory) path.emplace_back(p.x, p.y);
  lattice_ = LatticeCovering(truth.walls, path, resolution_m,
                             std::max(kMarginM, kMarginCells * resolution_m));
  walls_ = SegmentField(lattice_, truth.walls);
  if (!truth.gone.empty()) {
    walls_now_ = SegmentField(lattice_, truth.walls_now);
    gone_ = SegmentField(lattice_, truth.gone);
  }
  if (true_trajectory.empty()) return;
  const Pose2& first = true_trajectory.front();
  std::vector<Segment> legs = {{first.x, first.y, first.x, first.y}};  // one pose: itself
  for (std::size_t i = 1; i < true_trajectory.size(); ++i) {
    const Pose2 &a = true_trajectory[i - 1], &b = true_trajectory[i];
    legs.push_back({a.x, a.y, b.x, b.y});
  }
  trajectory_distance_ = DistanceTransform(DrawSegments(lattice_, legs));
}

OccupancyGrid TruthRaster::WallGrid() const {
  return GridOn(lattice_,
                [this](const LatticeCell& c) { return !walls_.empty() && walls_.Holds(c); });
}

OccupancyGrid RasterizeWalls(const std::vector<Segment>& walls, double resolution_m,
                             double margin_m) {
  const Lattice l = LatticeCovering(walls, {}, resolution_m, margin_m);
  const cv::Mat img = DrawSegments(l, walls);
  return GridOn(l, [&img](const LatticeCell& c) { return img.at<uchar>(c.row, c.col) == 0; });
}

}  // namespace lifelong::eval
