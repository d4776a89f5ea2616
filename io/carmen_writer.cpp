// CARMEN log writer; see carmen_log.hpp for the format and the guarantees.
#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/carmen_log.hpp"
#include "io/text_fields.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

// Every field follows a token, so AppendFixed's separator is always written.
void Put(std::string* s, double v, int decimals) { AppendFixed(s, v, decimals); }
void PutPose(std::string* s, const Pose2& p) {
  Put(s, p.x, 6);
  Put(s, p.y, 6);
  Put(s, p.theta, 6);
}
void PutStamp(std::string* s, double stamp_s) {
  Put(s, stamp_s, 6);
  s->append(" lifelong");
  Put(s, stamp_s, 6);
}
void CheckFinite(double v, const char* field) {
  if (!std::isfinite(v))
    throw std::invalid_argument(std::string("CarmenWriter: ") + field + " is not finite");
}

}  // namespace

CarmenWriter::CarmenWriter(const std::string& path) : path_(path), tmp_path_(TempPathFor(path)) {
  const bool gz = path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0;
  file_ = gzopen(tmp_path_.c_str(), gz ? "wb6" : "wT");
  if (file_ == nullptr) throw InputError(path, 0, "", "cannot open for writing");
  WriteLine("# CARMEN log written by lifelong");
  WriteLine("# PARAM name value host timestamp");
  WriteLine("# ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp");
  WriteLine(
      "# ROBOTLASER1 laser_type start_angle fov angular_res max_range accuracy "
      "remission_mode num_readings [range_readings] num_remissions [remissions] laser_x "
      "laser_y laser_theta robot_x robot_y robot_theta tv rv forward_safety_dist "
      "side_safety_dist turn_axis ipc_timestamp ipc_hostname logger_timestamp");
  WriteLine(
      "# TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta ipc_timestamp "
      "ipc_hostname logger_timestamp (ground truth of the scan just before, if known)");
}

CarmenWriter::~CarmenWriter() {
  if (file_ == nullptr) return;
  gzclose(static_cast<gzFile>(file_));
  std::remove(tmp_path_.c_str());
}

void CarmenWriter::WriteLine(const std::string& line) {
  if (file_ == nullptr) throw std::logic_error("CarmenWriter: write after Close");
  auto* f = static_cast<gzFile>(file_);
  if (gzputs(f, line.c_str()) < 0 || gzputc(f, '\n') < 0) {
    throw InputError(path_, 0, "", "write failed");
  }
}

void CarmenWriter::WriteParam(const std::string& name, const std::string& value) {
  WriteLine("PARAM " + name + " " + value + " lifelong 0");
}

void CarmenWriter::WriteOdometry(const Odometry& odometry) {
  const Pose2& p = odometry.T_odom_robot;
  for (double v : {p.x, p.y, p.theta, odometry.stamp_s}) CheckFinite(v, "odometry");
  std::string s = "ODOM";
  PutPose(&s, p);
  s.append(" 0 0 0");
  PutStamp(&s, odometry.stamp_s);
  WriteLine(s);
}

void CarmenWriter::WriteScan(const Observation& o) {
  const LaserScan& scan = o.scan;
  const double n = static_cast<double>(scan.ranges_m.size());
  std::string s = "ROBOTLASER1 0";
  Put(&s, scan.angle_min_rad, 9);
  Put(&s, scan.angle_increment_rad * std::max(n - 1.0, 0.0), 9);
  Put(&s, scan.angle_increment_rad, 9);
  Put(&s, scan.range_max_m, 4);
  s.append(" 0.01 0 ");
  s.append(std::to_string(scan.ranges_m.size()));
  for (float r : scan.ranges_m) {
    CheckFinite(r, "range");
    Put(&s, r, 4);
  }
  s.append(" 0");
  PutPose(&s, o.T_odom_robot * scan.T_robot_laser);
  PutPose(&s, o.T_odom_robot);
  s.append(" 0 0 0 0 0");
  PutStamp(&s, o.stamp_s);
  WriteLine(s);
  if (o.T_world_robot_true) {
    std::string t = "TRUEPOS";
    PutPose(&t, *o.T_world_robot_true);
    PutPose(&t, o.T_odom_robot);
    PutStamp(&t, o.stamp_s);
    WriteLine(t);
  }
}

void CarmenWriter::Close() {
  if (file_ == nullptr) return;
  const int rc = gzclose(static_cast<gzFile>(file_));
  file_ = nullptr;
  if (rc != Z_OK) {
    std::remove(tmp_path_.c_str());
    throw InputError(path_, 0, "", "cannot finish writing the file");
  }
  CommitTempFile(tmp_path_, path_);
}

}  // namespace lifelong::io
