// CARMEN log reader; see carmen_log.hpp for the formats and conventions.
#include "io/carmen_log.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "io/carmen_recovery.hpp"
#include "sensor/input_bounds.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

/// Reads a plain or gzipped text file line by line (zlib reads both transparently).
class GzLines {
 public:
  explicit GzLines(const std::string& path) : path_(path), file_(gzopen(path.c_str(), "rb")) {
    if (file_ == nullptr) throw InputError(path, 0, "", "cannot open file");
  }
  ~GzLines() { gzclose(file_); }
  GzLines(const GzLines&) = delete;
  GzLines& operator=(const GzLines&) = delete;

  bool Next(std::string* line) {
    line->clear();
    char buf[1 << 16];
    for (z_off_t before = gztell(file_); gzgets(file_, buf, sizeof buf) != nullptr;) {
      // gzgets copies NUL bytes too; strlen would silently cut the line there.
      const std::size_t n = std::strlen(buf);
      const z_off_t after = gztell(file_);
      if (after - before != static_cast<z_off_t>(n)) {
        throw InputError(path_, line_number_ + 1, "", "NUL byte in a text log (binary file?)");
      }
      before = after;
      line->append(buf, n);
      if (!line->empty() && line->back() == '\n') break;
    }
    int err = Z_OK;
    const char* msg = gzerror(file_, &err);
    if (err != Z_OK && err != Z_STREAM_END) {
      throw InputError(path_, line_number_ + 1, "", std::string("corrupt gzip data: ") + msg);
    }
    if (line->empty()) return false;
    ++line_number_;
    return true;
  }
  int line_number() const { return line_number_; }

 private:
  std::string path_;
  gzFile file_;
  int line_number_ = 0;
};

std::vector<std::string_view> Split(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

/// A number in an error message: short, whatever its size.
std::string Show(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

/// Walks the fields of one message, throwing line-numbered InputErrors.
class Fields {
 public:
  Fields(const std::vector<std::string_view>& tokens, const std::string& path, int line)
      : tokens_(tokens), path_(path), line_(line) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& message) const {
    throw InputError(path_, line_, field, message);
  }
  void Need(std::size_t count, const std::string& field) const {
    if (tokens_.size() < i_ + count) {
      Fail(field, std::string(tokens_[0]) + " line too short: " + std::to_string(tokens_.size()) +
                      " fields, expected at least " + std::to_string(i_ + count));
    }
  }
  double Number(const std::string& field) {
    Need(1, field);
    const std::string_view t = tokens_[i_++];
    double v = 0.0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size())
      Fail(field, "not a number: '" + std::string(t) + "'");
    if (!std::isfinite(v)) Fail(field, "not a finite number: '" + std::string(t) + "'");
    return v;
  }
  int Count(const std::string& field) {
    const double v = Number(field);
    if (v < 0.0 || v != std::floor(v) || v > 1e6) Fail(field, "not a valid count");
    return static_cast<int>(v);
  }
  /// A number within [lo, hi].
  double Within(const std::string& field, double lo, double hi, const char* what) {
    const double v = Number(field);
    if (v < lo || v > hi) Fail(field, Show(v) + " is out of range: " + what);
    return v;
  }
  double Coordinate(const std::string& field) {
    return Within(field, -kMaxCoordinateM, kMaxCoordinateM, "beyond 1e7 m of the origin");
  }
  Pose2 Pose(const std::string& field) {
    const std::string p = field.empty() ? "" : field + "_";
    const double x = Coordinate(p + "x"), y = Coordinate(p + "y");
    return {x, y, Number(p + "theta")};
  }
  std::string Word(const std::string& field) {
    Need(1, field);
    return std::string(tokens_[i_++]);
  }
  /// `ipc_timestamp ipc_hostname logger_timestamp`, which must end the line.
  double Stamp() {
    const char* what = "beyond 1e10 s (the year 2286 as Unix time)";
    const double ipc = Within("ipc_timestamp", -kMaxStampS, kMaxStampS, what);
    Word("ipc_hostname");
    Within("logger_timestamp", -kMaxStampS, kMaxStampS, what);
    if (i_ != tokens_.size()) {
      Fail(std::string(tokens_[0]),
           "line has " + std::to_string(tokens_.size() - i_) + " extra fields (beam count wrong?)");
    }
    return ipc;
  }
  std::vector<float> Ranges(int n) {
    Need(static_cast<std::size_t>(n), "range_readings");
    std::vector<float> r(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < r.size(); ++i) {
      const double v = Number("range_readings");
      if (v < 0.0 || v > kMaxCoordinateM) {
        Fail("range_readings", "beam " + std::to_string(i) + " has range " + Show(v) +
                                   " m (ranges are >= 0; 0 is no return)");
      }
      r[i] = static_cast<float>(v);
    }
    return r;
  }
  std::size_t size() const { return tokens_.size(); }

 private:
  const std::vector<std::string_view>& tokens_;
  const std::string& path_;
  int line_;
  std::size_t i_ = 1;
};

/// FLASER n r_1..r_n x y theta odom_x odom_y odom_theta ipc_timestamp host logger_timestamp
struct FlaserMessage {
  Observation observation;
  Pose2 T_world_robot;  ///< first pose triple (corrected in GMapping logs)
};
FlaserMessage ParseFlaser(Fields& f) {
  FlaserMessage m;
  LaserScan& scan = m.observation.scan;
  const int n = f.Count("num_readings");
  if (n == 0) f.Fail("num_readings", "a scan with 0 beams");
  if (f.size() != static_cast<std::size_t>(n) + 11) {
    f.Fail("num_readings", "announces " + std::to_string(n) + " beams but the line has " +
                               std::to_string(f.size()) + " fields, expected " +
                               std::to_string(n + 11));
  }
  scan.ranges_m = f.Ranges(n);
  const double step_deg = (n % 2 == 1 && n > 1) ? 180.0 / (n - 1) : 180.0 / std::max(n, 1);
  scan.angle_min_rad = -90.0 * kDeg;
  scan.angle_increment_rad = step_deg * kDeg;
  m.T_world_robot = f.Pose("");
  m.observation.T_odom_robot = f.Pose("odom");
  m.observation.stamp_s = scan.stamp_s = f.Stamp();
  return m;
}

/// ROBOTLASER1 type start fov res max_range accuracy remission_mode n r.. n_rem rem..
///   laser_x laser_y laser_theta robot_x robot_y robot_theta tv rv fwd side turn stamps
Observation ParseRobotLaser(Fields& f) {
  Observation o;
  LaserScan& scan = o.scan;
  f.Number("laser_type");
  scan.angle_min_rad = f.Within("start_angle", -2.0 * kPi, 2.0 * kPi, "beyond a full turn");
  const double fov = f.Within("fov", 0.0, 2.0 * kPi + 1e-6, "a field of view is in (0, 2 pi]");
  if (!(fov > 0.0)) f.Fail("fov", "a field of view is in (0, 2 pi]");
  const double res = f.Within("angular_res", 0.0, kPi, "the angle between beams is in [0, pi]");
  scan.range_max_m = f.Within("max_range", 0.0, kMaxCoordinateM, "not a sensor range");
  if (!(scan.range_max_m > 0.0)) f.Fail("max_range", "a sensor's maximum range is > 0");
  f.Number("accuracy");
  f.Number("remission_mode");
  const int n = f.Count("num_readings");
  if (n == 0) f.Fail("num_readings", "a scan with 0 beams");
  scan.ranges_m = f.Ranges(n);
  const int n_rem = f.Count("num_remissions");
  for (int i = 0; i < n_rem; ++i) f.Number("remissions");
  scan.angle_increment_rad = res > 0.0 ? res : (n > 1 ? fov / (n - 1) : 0.0);
  if (scan.angle_increment_rad * (n - 1) > 2.0 * kPi + 1e-6) {
    f.Fail("angular_res",
           std::to_string(n) + " beams " + Show(res) + " rad apart span more than a full turn");
  }
  const Pose2 laser = f.Pose("laser");
  o.T_odom_robot = f.Pose("robot");
  scan.T_robot_laser = Between(o.T_odom_robot, laser);
  for (const char* name : {"tv", "rv", "forward_safety_dist", "side_safety_dist", "turn_axis"}) {
    f.Number(name);
  }
  o.stamp_s = scan.stamp_s = f.Stamp();
  return o;
}

/// ODOM x y theta tv rv accel ipc_timestamp host logger_timestamp
Odometry ParseOdom(Fields& f) {
  Odometry o;
  o.T_odom_robot = f.Pose("");
  f.Number("tv");
  f.Number("rv");
  f.Number("accel");
  o.stamp_s = f.Stamp();
  return o;
}

/// PARAM name value [host timestamp]; a value may hold spaces.
CarmenParam ParseParam(const std::vector<std::string_view>& t, Fields& f) {
  f.Need(2, "param_value");
  CarmenParam p{std::string(t[1]), std::string(t[2])};
  const std::size_t end = t.size() >= 5 ? t.size() - 2 : t.size();
  for (std::size_t i = 3; i < end; ++i) p.value += " " + std::string(t[i]);
  return p;
}

/// TRUEPOS true_x true_y true_theta odom_x odom_y odom_theta stamps: attached to the scan
/// on the line just before it when the stamps agree (as CarmenWriter writes it).
bool AttachTruePose(Fields& f, Observation* previous_scan) {
  const Pose2 truth = f.Pose("true");
  f.Pose("odom");
  const double stamp = f.Stamp();
  if (previous_scan == nullptr || previous_scan->stamp_s != stamp) return false;
  if (previous_scan->T_world_robot_true) return false;
  previous_scan->T_world_robot_true = truth;
  return true;
}

template <typename T>
int CountBackward(const std::vector<T>& v) {
  int n = 0;
  for (std::size_t i = 1; i < v.size(); ++i) n += v[i].stamp_s < v[i - 1].stamp_s ? 1 : 0;
  return n;
}

/// The file line of the first scan stamped earlier than the scan before it; 0: none.
int FirstBackwardLine(const std::vector<Observation>& scans, const std::vector<int>& lines) {
  for (std::size_t i = 1; i < scans.size(); ++i) {
    if (scans[i].stamp_s < scans[i - 1].stamp_s) return lines[i];
  }
  return 0;
}

/// Whether to recover the raw odometry of a corrected log (kAuto: when it has the pattern);
/// InputError for GMapping output whose odometry cannot be recovered.
bool ShouldRecover(OdometryRecovery recovery, const std::vector<Event>& events,
                   const CarmenLog& log, bool has_flasers, const std::string& path) {
  if (recovery != OdometryRecovery::kAuto) return recovery == OdometryRecovery::kOn;
  int scans = 0, broken = 0;
  const bool recover = LooksCorrected(events, log, &scans, &broken);
  if (!recover && log.skipped.count("NEFF") > 0 && has_flasers) {
    throw InputError(path, 0, "NEFF",
                     "GMapping output (NEFF lines) whose raw odometry cannot be recovered: " +
                         std::to_string(broken) + " of " + std::to_string(scans) +
                         " scans lack the pattern (an ODOM of the scan's stamp just before "
                         "it, one repeating its corrected pose just after it); replaying the "
                         "corrected poses as odometry would score GMapping, not the mapper");
  }
  return recover;
}

}  // namespace

CarmenLog ReadCarmenLog(const std::string& path, const CarmenReadOptions& options) {
  CarmenLog log;
  GzLines lines(path);
  std::vector<Event> events;
  std::vector<std::size_t> flasers;
  std::vector<int> scan_lines;  // file line of each observation
  float flaser_max = 0.0f;
  bool previous_was_scan = false;
  std::string line;
  while (lines.Next(&line)) {
    const auto tokens = Split(line);
    if (tokens.empty()) continue;
    if (tokens[0][0] == '#') {
      ++log.comment_lines;
      continue;
    }
    Fields f(tokens, path, lines.line_number());
    const std::string_view type = tokens[0];
    Observation* previous_scan = previous_was_scan ? &log.observations.back() : nullptr;
    previous_was_scan = type == "FLASER" || type == "ROBOTLASER1";
    if (type == "FLASER") {
      FlaserMessage m = ParseFlaser(f);
      for (float r : m.observation.scan.ranges_m) flaser_max = std::max(flaser_max, r);
      flasers.push_back(log.observations.size());
      scan_lines.push_back(lines.line_number());
      events.push_back({true, log.observations.size(), lines.line_number(), m.T_world_robot});
      log.observations.push_back(std::move(m.observation));
    } else if (type == "ROBOTLASER1") {
      log.observations.push_back(ParseRobotLaser(f));  // never GMapping-corrected
      scan_lines.push_back(lines.line_number());
    } else if (type == "ODOM") {
      events.push_back({false, log.odometry.size(), lines.line_number(), Pose2()});
      log.odometry.push_back(ParseOdom(f));
    } else if (type == "TRUEPOS" && AttachTruePose(f, previous_scan)) {
      continue;
    } else if (type == "PARAM") {
      log.params.push_back(ParseParam(tokens, f));
    } else {
      ++log.skipped[std::string(type)];
    }
  }
  const double range_max =
      options.flaser_range_max_m > 0.0 ? options.flaser_range_max_m : flaser_max;
  for (std::size_t i : flasers) log.observations[i].scan.range_max_m = range_max;

  const bool recover = ShouldRecover(options.recovery, events, log, !flasers.empty(), path);
  if (recover) RecoverOdometry(events, path, &log);
  log.backward_scan_stamps = CountBackward(log.observations);
  log.first_backward_scan_line = FirstBackwardLine(log.observations, scan_lines);
  log.backward_odom_stamps = CountBackward(log.odometry);
  return log;
}

}  // namespace lifelong::io
