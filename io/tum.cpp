// TUM trajectory files; see tum.hpp.
#include "io/tum.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>

#include "io/text_fields.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {

void WriteTum(const std::string& path, const std::vector<StampedPose>& poses) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw InputError(path, 0, "", "cannot open for writing");
    for (const StampedPose& p : poses) {
      std::string s;
      AppendFixed(&s, p.stamp_s, 6);
      AppendFixed(&s, p.T_world_robot.x, 6);
      AppendFixed(&s, p.T_world_robot.y, 6);
      AppendFixed(&s, 0.0, 6);
      AppendFixed(&s, 0.0, 9);
      AppendFixed(&s, 0.0, 9);
      AppendFixed(&s, std::sin(0.5 * p.T_world_robot.theta), 9);
      AppendFixed(&s, std::cos(0.5 * p.T_world_robot.theta), 9);
      out << s << '\n';
    }
    if (!out.flush()) throw InputError(path, 0, "", "write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(path, 0, "", "cannot rename the temporary file into place");
  }
}

std::vector<StampedPose> ReadTum(const std::string& path) {
  std::vector<StampedPose> poses;
  ForEachNumericRow(path, {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"},
                    [&](int line, const std::vector<double>& v) {
                      const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
                      if (qx * qx + qy * qy + qz * qz + qw * qw < 1e-12) {
                        throw InputError(path, line, "qw", "zero quaternion");
                      }
                      // Yaw (ZYX convention); invariant to the quaternion's norm.
                      const double yaw = std::atan2(2.0 * (qw * qz + qx * qy),
                                                    qw * qw + qx * qx - qy * qy - qz * qz);
                      poses.push_back({v[0], Pose2(v[1], v[2], yaw)});
                    });
  return poses;
}

}  // namespace lifelong::io
