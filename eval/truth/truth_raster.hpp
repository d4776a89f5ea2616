// The truth's surfaces on a raster, made once per run (issue #32): every surface that stood,
// those standing at the end and those gone, each drawn with cv::line and distance-transformed
// (cv::distanceTransform, DIST_L2, DIST_MASK_PRECISE, which is exact, so a cell's distance
// does not depend on the raster's extent), and the true trajectory's distance for the
// visibility limit of wall recall. Blur, current blur and stale cells of every mode read it
// (eval/metrics/map_quality.hpp), and truth/map.pgm is its walls.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "eval/truth/ground_truth.hpp"
#include "sensor/pose2.hpp"
#include "types/occupancy_grid.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

/// A cell of a Lattice; it may lie outside the lattice's extent.
struct LatticeCell {
  int col = 0, row = 0;
};

/// Square cells in the truth frame: cell (col, row) covers [ox + col * res, ox + (col + 1) *
/// res) × [oy + row * res, ...), row 0 lowest y.
struct Lattice {
  double ox = 0.0, oy = 0.0, res = 0.05;
  int cols = 0, rows = 0;

  /// The cell holding (x, y). The epsilon keeps a point exactly on a cell border (walls at
  /// x = 2.0) in one cell.
  LatticeCell CellOf(double x, double y) const;
  bool Inside(const LatticeCell& c) const {
    return c.col >= 0 && c.row >= 0 && c.col < cols && c.row < rows;
  }
  std::size_t Index(const LatticeCell& c) const {
    return static_cast<std::size_t>(c.row) * static_cast<std::size_t>(cols) +
           static_cast<std::size_t>(c.col);
  }
  std::size_t size() const {
    return static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows);
  }
  double CentreX(int col) const { return ox + (col + 0.5) * res; }
  double CentreY(int row) const { return oy + (row + 0.5) * res; }
};

/// The smallest lattice on multiples of res from the origin that covers every segment's end
/// points and `points` (x, y pairs), plus margin_m on each side.
Lattice LatticeCovering(const std::vector<Segment>& segments,
                        const std::vector<std::pair<double, double>>& points, double res,
                        double margin_m);

/// Every lattice cell's distance in cells to the nearest of `targets` (cells inside the
/// lattice; the others are ignored), row-major; empty when no target is inside.
std::vector<float> DistanceToCells(const Lattice& lattice, const std::vector<LatticeCell>& targets);

/// Segments drawn on a lattice (8-connected lines) with every cell's distance to the nearest
/// drawn cell.
class SegmentField {
 public:
  SegmentField() = default;
  SegmentField(const Lattice& lattice, std::vector<Segment> segments);

  bool empty() const { return segments_.empty(); }
  const std::vector<Segment>& segments() const { return segments_; }
  /// m, the segments' summed length.
  double length_m() const;
  /// Whether a segment crosses cell c (inside the lattice).
  bool Holds(const LatticeCell& c) const { return distance_[lattice_.Index(c)] == 0.0f; }
  /// Cells from c to the nearest drawn cell. Inside the lattice, between cell centres (the
  /// distance transform); beyond it, from c's centre to the nearest segment. Infinite when
  /// there is no segment.
  double DistanceCells(const LatticeCell& c) const;

 private:
  Lattice lattice_;
  std::vector<Segment> segments_;
  std::vector<float> distance_;  ///< row-major over the lattice
};

/// The truth of a run on one lattice at the map resolution. Its extent covers every surface
/// and the true trajectory plus max(1 m, 4 cells).
class TruthRaster {
 public:
  TruthRaster(const GroundTruth& truth, const std::vector<Pose2>& true_trajectory,
              double resolution_m);

  const Lattice& lattice() const { return lattice_; }
  /// Whether `map` is at the raster's resolution (a map at another is scored on a raster of
  /// its own).
  bool Fits(const OccupancyGrid& map) const {
    return std::abs(map.resolution_m - lattice_.res) <= 1e-9 * lattice_.res;
  }
  /// Every surface that stood during the run (GroundTruth::walls).
  const SegmentField& walls() const { return walls_; }
  /// The surfaces standing at the end and those gone by then; both empty when the world did
  /// not change.
  const SegmentField& walls_now() const { return walls_now_; }
  const SegmentField& gone() const { return gone_; }
  bool has_trajectory() const { return !trajectory_distance_.empty(); }
  /// m from cell c (inside the lattice) to the true trajectory's nearest cell.
  double TrajectoryDistanceM(const LatticeCell& c) const {
    return static_cast<double>(trajectory_distance_[lattice_.Index(c)]) * lattice_.res;
  }
  /// The walls as an occupancy grid (p = 1 on walls, 0 elsewhere): truth/map.pgm.
  OccupancyGrid WallGrid() const;

 private:
  Lattice lattice_;
  SegmentField walls_, walls_now_, gone_;
  std::vector<float> trajectory_distance_;
};

/// An occupancy grid holding `walls` rasterized (p = 1 on walls, 0 elsewhere) on the lattice
/// covering them plus margin_m. Useful as a simulated log's truth map and as a perfect map in
/// tests.
OccupancyGrid RasterizeWalls(const std::vector<Segment>& walls, double resolution_m,
                             double margin_m = 1.0);

}  // namespace lifelong::eval
