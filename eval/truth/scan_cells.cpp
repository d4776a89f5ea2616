#include "eval/truth/scan_cells.hpp"

#include <cmath>
#include <stdexcept>

#include "eval/truth/sightings.hpp"

namespace lifelong::eval {

std::int64_t ScanCells(const std::vector<Observation>& stream,
                       const std::vector<std::size_t>& scans, const std::vector<Pose2>& poses,
                       double resolution_m, double max_range_m) {
  if (scans.size() != poses.size()) throw std::invalid_argument("ScanCells: sizes differ");
  if (!(resolution_m > 0.0)) throw std::invalid_argument("ScanCells: resolution <= 0");
  CellSet cells(resolution_m);
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const LaserScan& scan = stream.at(scans[k]).scan;
    const Pose2 laser = poses[k] * scan.T_robot_laser;
    const double c = std::cos(laser.theta), s = std::sin(laser.theta);
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      if (!scan.IsReturn(i) || scan.ranges_m[i] > max_range_m) continue;
      const double r = scan.ranges_m[i], a = scan.Bearing(i);
      const double lx = r * std::cos(a), ly = r * std::sin(a);
      cells.Add(laser.x + c * lx - s * ly, laser.y + s * lx + c * ly);
    }
  }
  return static_cast<std::int64_t>(cells.Size());
}

}  // namespace lifelong::eval
