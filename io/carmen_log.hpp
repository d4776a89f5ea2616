// CARMEN text logs (plain or gzipped): the robot-log format of the CARMEN toolkit
// (Montemerlo et al. 2003), as used by the Intel and FHW logs of the seed (Kretzschmar
// 2009, ch. 6). Message layouts: /work/shared/datasets/SOURCES.md.
//
// Reader: FLASER, ROBOTLASER1, ODOM, PARAM and `#` comments; every other message type is
// counted and skipped, except a TRUEPOS right after a scan with the same stamp (as
// CarmenWriter writes ground truth), which fills that scan's T_world_robot_true. FLASER carries no
// field of view: 180 deg is assumed, beam 0 at -90 deg, step 180/n deg for even n (180 -> 1 deg)
// and 180/(n-1) deg for odd n (181, 361). ROBOTLASER1 gives start angle, resolution, max range, and
// the laser and robot poses, from which T_robot_laser = Between(robot pose, laser pose).
//
// GMapping-corrected logs (FLASER poses are corrected estimates) get their raw odometry
// back: the ODOM line just before scan k equals corrected_{k-1} * raw step, so
// Delta_k = Between(corrected_{k-1}, ODOM_before_k) with corrected_{-1} = identity, and the
// raw pose of scan k is Delta_0 * ... * Delta_k. The ODOM after each FLASER (garbage stamp)
// is dropped; the ODOMs in between are mapped into the raw frame the same way.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "sensor/observation.hpp"
#include "types/stamped_pose.hpp"

namespace lifelong::io {

enum class OdometryRecovery {
  kAuto,  ///< recover when every FLASER shows the GMapping pattern (see LooksCorrected);
          ///< NEFF lines without the pattern throw rather than guess
  kOn,    ///< always treat the FLASER poses as corrected estimates
  kOff,   ///< never: the FLASER odometry triple is used as is
};

struct CarmenReadOptions {
  /// m; FLASER readings >= this are "no return". <= 0: the log's largest FLASER reading.
  double flaser_range_max_m = 0.0;
  OdometryRecovery recovery = OdometryRecovery::kAuto;
};

struct CarmenParam {
  std::string name;
  std::string value;
};

struct CarmenLog {
  std::vector<Observation> observations;  ///< one per FLASER / ROBOTLASER1, file order
  std::vector<Odometry> odometry;         ///< ODOM messages, file order
  std::vector<CarmenParam> params;
  std::map<std::string, int> skipped;  ///< message type -> count (NEFF, SYNC, RLASER, ...)
  int comment_lines = 0;
  int backward_scan_stamps = 0;      ///< scans stamped earlier than the scan before them
  int first_backward_scan_line = 0;  ///< file line of the first such scan; 0: none
  int backward_odom_stamps = 0;      ///< ODOMs stamped earlier than the ODOM before them
  bool odometry_recovered = false;   ///< FLASER poses were corrected; raw odometry rebuilt
  /// The corrected FLASER poses, one per scan, when odometry_recovered: the log's own
  /// reference trajectory (the corrected estimate it was published with).
  std::vector<StampedPose> corrected_poses;
  int dropped_odometry = 0;  ///< ODOM lines dropped by the recovery (after FLASER)
  /// Scans of a corrected log with no ODOM of their own before them (Observation::
  /// odometry_lost), and the file line of the first; 0: none.
  int lost_odometry_scans = 0;
  int first_lost_odometry_line = 0;
};

/// Reads a CARMEN log; throws lifelong::InputError(path, line, field, ...) on a missing
/// file or any truncated or corrupt line.
CarmenLog ReadCarmenLog(const std::string& path, const CarmenReadOptions& options = {});

/// Writes a CARMEN log: a header comment, then PARAM, ODOM and ROBOTLASER1 lines in call
/// order, each scan with a known true pose followed by a TRUEPOS line. Scans are written as
/// ROBOTLASER1 only (never also FLASER, which would duplicate each scan for a reader): it carries
/// angles, max range and the laser mount exactly. Poses print with 6 decimals, ranges with 4,
/// angles with 9; the same calls give byte-identical files. Output goes to TempPathFor(path)
/// (io/atomic_file.hpp), renamed to `path` on Close(); an unclosed writer removes its temporary
/// file. A path ending in ".gz" is gzipped.
class CarmenWriter {
 public:
  explicit CarmenWriter(const std::string& path);
  ~CarmenWriter();
  CarmenWriter(const CarmenWriter&) = delete;
  CarmenWriter& operator=(const CarmenWriter&) = delete;

  void WriteParam(const std::string& name, const std::string& value);
  void WriteOdometry(const Odometry& odometry);
  void WriteScan(const Observation& observation);
  /// Flushes, closes and renames the temporary file into place. Throws InputError on failure.
  void Close();

 private:
  void WriteLine(const std::string& line);

  std::string path_;
  std::string tmp_path_;
  void* file_ = nullptr;  ///< gzFile (zlib), opened transparent for plain text
};

}  // namespace lifelong::io
