#include "eval/metrics/map_quality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/metrics/metrics.hpp"

namespace lifelong::eval {
namespace {

/// A raster in the truth frame: cell (col,row) covers [ox + col*res, ...), row 0 lowest y.
struct Raster {
  double ox = 0.0, oy = 0.0, res = 0.05;
  int cols = 0, rows = 0;
  cv::Point Cell(double x, double y) const {
    // The epsilon keeps points exactly on a cell border (walls at x = 2.0) in one cell.
    return {static_cast<int>(std::floor((x - ox) / res + 1e-9)),
            static_cast<int>(std::floor((y - oy) / res + 1e-9))};
  }
  bool Inside(const cv::Point& c) const { return c.x >= 0 && c.y >= 0 && c.x < cols && c.y < rows; }
  cv::Mat Blank() const { return cv::Mat(rows, cols, CV_8UC1, cv::Scalar(255)); }
};

struct Box {
  double x0 = std::numeric_limits<double>::max(), y0 = x0;
  double x1 = std::numeric_limits<double>::lowest(), y1 = x1;
  void Add(double x, double y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
};

/// Covers `box` plus margin_m, on the lattice of (lattice_x, lattice_y) so that an
/// unaligned estimate's cells coincide with the truth raster's cells.
Raster MakeRaster(const Box& box, double res, double margin_m, double lattice_x, double lattice_y) {
  Raster r;
  r.res = res;
  r.ox = lattice_x + std::floor((box.x0 - margin_m - lattice_x) / res) * res;
  r.oy = lattice_y + std::floor((box.y0 - margin_m - lattice_y) / res) * res;
  r.cols = static_cast<int>(std::ceil((box.x1 + margin_m - r.ox) / res)) + 1;
  r.rows = static_cast<int>(std::ceil((box.y1 + margin_m - r.oy) / res)) + 1;
  return r;
}

/// Walls as zero pixels on 255 (the convention cv::distanceTransform measures to).
cv::Mat DrawWalls(const Raster& r, const std::vector<Segment>& walls) {
  cv::Mat img = r.Blank();
  for (const Segment& s : walls) {
    cv::line(img, r.Cell(s.x0, s.y0), r.Cell(s.x1, s.y1), cv::Scalar(0), 1, cv::LINE_8);
  }
  return img;
}

/// Distance in cells from every pixel to the nearest zero pixel.
cv::Mat DistanceCells(const cv::Mat& zeros_are_targets) {
  cv::Mat dist;
  cv::distanceTransform(zeros_are_targets, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return dist;
}

std::vector<cv::Point2d> OccupiedCentres(const OccupancyGrid& map, const Pose2& T,
                                         float threshold) {
  std::vector<cv::Point2d> pts;
  for (int row = 0; row < map.height; ++row) {
    for (int col = 0; col < map.width; ++col) {
      if (map.At(col, row) < threshold) continue;
      double x = 0.0, y = 0.0;
      T.Apply(map.origin_x_m + (col + 0.5) * map.resolution_m,
              map.origin_y_m + (row + 0.5) * map.resolution_m, &x, &y);
      pts.emplace_back(x, y);
    }
  }
  return pts;
}

double WallLength(const std::vector<Segment>& walls) {
  double len = 0.0;
  for (const Segment& s : walls) len += std::hypot(s.x1 - s.x0, s.y1 - s.y0);
  return len;
}

}  // namespace

BlurResult ComputeBlur(const OccupancyGrid& map, const std::vector<Segment>& walls,
                       const Pose2& T_truth_est, const std::vector<Pose2>& true_trajectory,
                       const BlurConfig& config) {
  BlurResult out;
  const std::vector<cv::Point2d> occ = OccupiedCentres(map, T_truth_est, config.occupied_threshold);
  Box box;
  for (const Segment& s : walls) box.Add(s.x0, s.y0), box.Add(s.x1, s.y1);
  for (const cv::Point2d& p : occ) box.Add(p.x, p.y);
  for (const Pose2& p : true_trajectory) box.Add(p.x, p.y);
  if (walls.empty()) return out;
  const double res = map.resolution_m;
  const Raster r = MakeRaster(box, res, (config.recall_tolerance_cells + 2.0) * res, map.origin_x_m,
                              map.origin_y_m);
  const cv::Mat wall_img = DrawWalls(r, walls);
  const cv::Mat wall_dist = DistanceCells(wall_img);
  cv::Mat occ_img = r.Blank();
  std::vector<double> dist_cm;
  for (const cv::Point2d& p : occ) {
    const cv::Point c = r.Cell(p.x, p.y);
    occ_img.at<uchar>(c) = 0;
    dist_cm.push_back(wall_dist.at<float>(c) * res * 100.0);
  }
  out.occupied_cells = occ.size();
  if (!dist_cm.empty()) {
    double sum = 0.0;
    for (double d : dist_cm) sum += d;
    out.mean_cm = sum / static_cast<double>(dist_cm.size());
    out.p95_cm = Percentile(dist_cm, 0.95);
  }
  cv::Mat traj_dist;
  if (!true_trajectory.empty()) {
    cv::Mat traj_img = r.Blank();
    for (std::size_t i = 0; i < true_trajectory.size(); ++i) {
      const Pose2& a = true_trajectory[i];
      const Pose2& b = true_trajectory[i + 1 < true_trajectory.size() ? i + 1 : i];
      cv::line(traj_img, r.Cell(a.x, a.y), r.Cell(b.x, b.y), cv::Scalar(0), 1, cv::LINE_8);
    }
    traj_dist = DistanceCells(traj_img);
  }
  const cv::Mat occ_dist = DistanceCells(occ_img);
  std::size_t all_wall_cells = 0;
  for (int row = 0; row < r.rows; ++row) {
    for (int col = 0; col < r.cols; ++col) {
      if (wall_img.at<uchar>(row, col) != 0) continue;
      ++all_wall_cells;
      if (!traj_dist.empty() && traj_dist.at<float>(row, col) * res > config.visibility_range_m)
        continue;
      ++out.wall_cells;
      if (occ.empty() || occ_dist.at<float>(row, col) > config.recall_tolerance_cells) continue;
      ++out.wall_cells_recalled;
    }
  }
  out.wall_length_m = WallLength(walls) * static_cast<double>(out.wall_cells) /
                      static_cast<double>(std::max<std::size_t>(all_wall_cells, 1));
  if (out.wall_length_m > 0.0) out.thickness = static_cast<double>(occ.size()) / out.wall_length_m;
  if (out.wall_cells > 0) {
    out.recall = static_cast<double>(out.wall_cells_recalled) / static_cast<double>(out.wall_cells);
  }
  return out;
}

double StaleShare(const OccupancyGrid& map, const std::vector<Segment>& gone,
                  const std::vector<Segment>& now, const Pose2& T_truth_est,
                  const BlurConfig& config) {
  const std::vector<cv::Point2d> occ = OccupiedCentres(map, T_truth_est, config.occupied_threshold);
  if (occ.empty() || gone.empty()) return 0.0;
  Box box;
  for (const std::vector<Segment>* set : {&gone, &now}) {
    for (const Segment& s : *set) box.Add(s.x0, s.y0), box.Add(s.x1, s.y1);
  }
  for (const cv::Point2d& p : occ) box.Add(p.x, p.y);
  const double res = map.resolution_m;
  const Raster r = MakeRaster(box, res, (config.recall_tolerance_cells + 2.0) * res, map.origin_x_m,
                              map.origin_y_m);
  const cv::Mat gone_dist = DistanceCells(DrawWalls(r, gone));
  const cv::Mat now_dist = now.empty() ? cv::Mat() : DistanceCells(DrawWalls(r, now));
  std::size_t stale = 0;
  for (const cv::Point2d& p : occ) {
    const cv::Point c = r.Cell(p.x, p.y);
    const bool near_gone = gone_dist.at<float>(c) <= config.recall_tolerance_cells;
    const bool near_now =
        !now_dist.empty() && now_dist.at<float>(c) <= config.recall_tolerance_cells;
    stale += (near_gone && !near_now) ? 1 : 0;
  }
  return static_cast<double>(stale) / static_cast<double>(occ.size());
}

std::optional<double> ShownShare(const OccupancyGrid& map, const std::vector<Segment>& segments,
                                 const std::vector<Segment>& exclude, const Pose2& T_truth_est,
                                 const BlurConfig& config,
                                 const std::function<bool(double x, double y)>& counted) {
  if (segments.empty()) return std::nullopt;
  const std::vector<cv::Point2d> occ = OccupiedCentres(map, T_truth_est, config.occupied_threshold);
  Box box;
  for (const Segment& s : segments) box.Add(s.x0, s.y0), box.Add(s.x1, s.y1);
  const double res = map.resolution_m;
  const double margin = (config.recall_tolerance_cells + 2.0) * res;
  const Raster r = MakeRaster(box, res, margin, map.origin_x_m, map.origin_y_m);
  cv::Mat occ_img = r.Blank();
  for (const cv::Point2d& p : occ) {
    const cv::Point c = r.Cell(p.x, p.y);
    if (r.Inside(c)) occ_img.at<uchar>(c) = 0;
  }
  const cv::Mat occ_dist = DistanceCells(occ_img);
  const cv::Mat exclude_dist = exclude.empty() ? cv::Mat() : DistanceCells(DrawWalls(r, exclude));
  const cv::Mat cells = DrawWalls(r, segments);
  std::size_t cells_counted = 0, shown = 0;
  for (int row = 0; row < r.rows; ++row) {
    for (int col = 0; col < r.cols; ++col) {
      if (cells.at<uchar>(row, col) != 0) continue;
      if (!exclude_dist.empty() &&
          exclude_dist.at<float>(row, col) <= config.recall_tolerance_cells) {
        continue;
      }
      if (counted && !counted(r.ox + (col + 0.5) * res, r.oy + (row + 0.5) * res)) continue;
      ++cells_counted;
      shown += (!occ.empty() && occ_dist.at<float>(row, col) <= config.recall_tolerance_cells);
    }
  }
  if (cells_counted == 0) return std::nullopt;
  return static_cast<double>(shown) / static_cast<double>(cells_counted);
}

OccupancyGrid RasterizeWalls(const std::vector<Segment>& walls, double resolution_m,
                             double margin_m) {
  Box box;
  for (const Segment& s : walls) box.Add(s.x0, s.y0), box.Add(s.x1, s.y1);
  if (walls.empty()) box.Add(0.0, 0.0);
  const Raster r = MakeRaster(box, resolution_m, margin_m, 0.0, 0.0);
  const cv::Mat img = DrawWalls(r, walls);
  OccupancyGrid grid;
  grid.width = r.cols, grid.height = r.rows, grid.resolution_m = resolution_m;
  grid.origin_x_m = r.ox, grid.origin_y_m = r.oy;
  grid.p_occ.assign(static_cast<std::size_t>(r.cols) * static_cast<std::size_t>(r.rows), 0.0f);
  for (int row = 0; row < r.rows; ++row) {
    for (int col = 0; col < r.cols; ++col) {
      if (img.at<uchar>(row, col) == 0) grid.At(col, row) = 1.0f;
    }
  }
  return grid;
}

EntropyResult ComputeMapEntropy(const OccupancyGrid& map, float occupied_threshold) {
  EntropyResult out;
  for (float p : map.p_occ) {
    if (p < 0.0f) continue;
    ++out.known_cells;
    if (p >= occupied_threshold) ++out.occupied_cells;
    const double q = static_cast<double>(p);
    if (q > 0.0 && q < 1.0) out.entropy_bits -= q * std::log2(q) + (1.0 - q) * std::log2(1.0 - q);
  }
  if (out.known_cells > 0) {
    out.occupied_share =
        static_cast<double>(out.occupied_cells) / static_cast<double>(out.known_cells);
  }
  return out;
}

}  // namespace lifelong::eval
