// TUM trajectory files; see tum.hpp.
#include "io/tum.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

void Put(std::string* s, double v, int decimals) {
  char buf[512];
  const auto [end, ec] =
      std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  if (ec != std::errc()) throw std::invalid_argument("WriteTum: cannot format a number");
  if (!s->empty()) s->push_back(' ');
  s->append(buf, end);
}

double ParseNumber(const std::string& token, const std::string& path, int line, const char* field) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(v)) {
    throw InputError(path, line, field, "not a finite number: '" + token + "'");
  }
  return v;
}

}  // namespace

void WriteTum(const std::string& path, const std::vector<StampedPose>& poses) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw InputError(path, 0, "", "cannot open for writing");
    for (const StampedPose& p : poses) {
      std::string s;
      Put(&s, p.stamp_s, 6);
      Put(&s, p.T_world_robot.x, 6);
      Put(&s, p.T_world_robot.y, 6);
      Put(&s, 0.0, 6);
      Put(&s, 0.0, 9);
      Put(&s, 0.0, 9);
      Put(&s, std::sin(0.5 * p.T_world_robot.theta), 9);
      Put(&s, std::cos(0.5 * p.T_world_robot.theta), 9);
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
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  static constexpr const char* kFields[] = {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  std::vector<StampedPose> poses;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::istringstream tokens(text);
    std::string token;
    double v[8];
    int n = 0;
    while (tokens >> token) {
      if (n == 0 && token[0] == '#') break;
      if (n == 8) throw InputError(path, line, "", "more than 8 fields");
      v[n] = ParseNumber(token, path, line, kFields[n]);
      ++n;
    }
    if (n == 0) continue;
    if (n < 8)
      throw InputError(path, line, kFields[n],
                       "missing (line has " + std::to_string(n) + " of 8 fields)");
    const double qx = v[4], qy = v[5], qz = v[6], qw = v[7];
    if (qx * qx + qy * qy + qz * qz + qw * qw < 1e-12) {
      throw InputError(path, line, "qw", "zero quaternion");
    }
    // Yaw (ZYX convention); this form is invariant to the quaternion's norm.
    const double yaw = std::atan2(2.0 * (qw * qz + qx * qy), qw * qw + qx * qx - qy * qy - qz * qz);
    poses.push_back({v[0], Pose2(v[1], v[2], yaw)});
  }
  return poses;
}

}  // namespace lifelong::io
