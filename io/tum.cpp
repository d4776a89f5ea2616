// TUM trajectory files; see tum.hpp.
#include "io/tum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/text_fields.hpp"
#include "sensor/input_bounds.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

/// Yaw (ZYX convention) of the quaternion v[4..7] = (qx, qy, qz, qw), whatever its norm.
/// The components are divided by the largest magnitude first: squaring them as read
/// overflowed to inf for components near 1e200, and inf - inf made the yaw NaN.
double YawOf(const std::vector<double>& v, const std::string& name, int line) {
  const double scale = std::max({std::abs(v[4]), std::abs(v[5]), std::abs(v[6]), std::abs(v[7])});
  if (scale == 0.0) throw InputError(name, line, "qw", "zero quaternion");
  const double qx = v[4] / scale, qy = v[5] / scale, qz = v[6] / scale, qw = v[7] / scale;
  if (scale * std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw) < 1e-6) {
    throw InputError(name, line, "qw", "zero quaternion");  // |q| < 1e-6, as before
  }
  return std::atan2(2.0 * (qw * qz + qx * qy), qw * qw + qx * qx - qy * qy - qz * qz);
}

}  // namespace

void WriteTum(const std::string& path, const std::vector<StampedPose>& poses) {
  std::string text;
  for (const StampedPose& p : poses) {
    std::string s;  // one line; AppendFixed separates values with spaces
    AppendFixed(&s, p.stamp_s, 6);
    AppendFixed(&s, p.T_world_robot.x, 6);
    AppendFixed(&s, p.T_world_robot.y, 6);
    AppendFixed(&s, 0.0, 6);
    AppendFixed(&s, 0.0, 9);
    AppendFixed(&s, 0.0, 9);
    AppendFixed(&s, std::sin(0.5 * p.T_world_robot.theta), 9);
    AppendFixed(&s, std::cos(0.5 * p.T_world_robot.theta), 9);
    text += s + '\n';
  }
  WriteFileAtomically(path, text);
}

std::vector<StampedPose> ReadTum(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  return ParseTum(in, path);
}

std::vector<StampedPose> ParseTum(std::istream& in, const std::string& name) {
  std::vector<StampedPose> poses;
  // A quaternion of any norm gives its yaw (YawOf), so only stamps and positions are bounded.
  ForEachNumericRow(in, name, {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"},
                    [&](int line, const std::vector<double>& v) {
                      poses.push_back({v[0], Pose2(v[1], v[2], YawOf(v, name, line))});
                    },
                    {kMaxStampS, kMaxCoordinateM, kMaxCoordinateM, kMaxCoordinateM});
  return poses;
}

std::vector<StampedPose> ReadTrajectory(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  std::string text;
  std::size_t columns = 0;
  while (columns == 0 && std::getline(in, text)) {
    std::istringstream tokens(text);
    std::string token;
    while (tokens >> token && !(columns == 0 && token[0] == '#')) ++columns;
  }
  in.clear();
  in.seekg(0);
  std::vector<StampedPose> poses;
  if (columns == 8) {
    poses = ParseTum(in, path);
  } else if (columns == 4) {
    ForEachNumericRow(in, path, {"t", "x", "y", "theta"},
                      [&](int, const std::vector<double>& v) {
                        poses.push_back({v[0], Pose2(v[1], v[2], v[3])});
                      },
                      {kMaxStampS, kMaxCoordinateM, kMaxCoordinateM, kMaxCoordinateM});
  } else if (columns != 0) {
    throw InputError(path, 0, "",
                     "expected 8 fields a line (TUM: t x y z qx qy qz qw) or 4 (t x y theta), "
                     "the first line has " +
                         std::to_string(columns));
  }
  if (poses.empty()) throw InputError(path, 0, "", "no pose in the file");
  for (std::size_t k = 1; k < poses.size(); ++k) {
    if (poses[k].stamp_s <= poses[k - 1].stamp_s) {
      throw InputError(path, 0, "t",
                       "stamps must increase (poses are paired with scans by time): pose " +
                           std::to_string(k + 1) + " of " + std::to_string(poses.size()) +
                           " is not later than the one before");
    }
  }
  return poses;
}

}  // namespace lifelong::io
