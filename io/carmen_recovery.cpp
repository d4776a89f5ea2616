// GMapping-corrected logs; see carmen_recovery.hpp.
#include "io/carmen_recovery.hpp"

#include <algorithm>
#include <cmath>

#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

bool SamePose(const Pose2& a, const Pose2& b) {
  return std::abs(a.x - b.x) < 1e-9 && std::abs(a.y - b.y) < 1e-9 &&
         std::abs(NormalizeAngle(a.theta - b.theta)) < 1e-9;
}

}  // namespace

bool LooksCorrected(const std::vector<Event>& ev, const CarmenLog& log, int* scans, int* broken) {
  int stamps_off = 0;
  *scans = *broken = 0;
  for (std::size_t i = 0; i < ev.size(); ++i) {
    if (!ev[i].is_flaser) continue;
    ++*scans;
    if (i == 0 || ev[i - 1].is_flaser ||
        (i + 1 < ev.size() &&
         (ev[i + 1].is_flaser ||
          !SamePose(log.odometry[ev[i + 1].index].T_odom_robot, ev[i].corrected)))) {
      ++*broken;
    } else if (log.odometry[ev[i - 1].index].stamp_s != log.observations[ev[i].index].stamp_s) {
      ++stamps_off;
    }
  }
  const int allowed = std::max(1, *scans / 100);
  if (stamps_off > allowed) *broken += stamps_off;
  return *scans > 0 && *broken == 0;
}

void RecoverOdometry(const std::vector<Event>& ev, const std::string& path, CarmenLog* log) {
  Pose2 corrected_prev, raw_prev;
  std::vector<Odometry> odometry;
  for (std::size_t i = 0; i < ev.size(); ++i) {
    if (ev[i].is_flaser) {
      if (i == 0 || ev[i - 1].is_flaser) {
        throw InputError(path, ev[i].line, "ODOM",
                         "odometry recovery needs an ODOM line just before each scan");
      }
      const Pose2& odom_before = log->odometry[ev[i - 1].index].T_odom_robot;
      Observation& o = log->observations[ev[i].index];
      o.T_odom_robot = raw_prev * Between(corrected_prev, odom_before);
      // The ODOM before is the previous scan's repeat: no odometry was logged since it, and
      // the odometry after this scan is chained to this scan's corrected pose, so the step is
      // lost (seattle-corrected, one scan: GMapping turned 81 degrees there).
      if (i >= 2 && ev[i - 2].is_flaser) {
        o.odometry_lost = true;
        if (log->lost_odometry_scans++ == 0) log->first_lost_odometry_line = ev[i].line;
      }
      log->corrected_poses.push_back({o.stamp_s, ev[i].corrected});
      corrected_prev = ev[i].corrected;
      raw_prev = o.T_odom_robot;
    } else if (i > 0 && ev[i - 1].is_flaser) {
      ++log->dropped_odometry;  // repeats the corrected pose, garbage stamp
    } else {
      Odometry o = log->odometry[ev[i].index];
      o.T_odom_robot = raw_prev * Between(corrected_prev, o.T_odom_robot);
      odometry.push_back(o);
    }
  }
  log->odometry = std::move(odometry);
  log->odometry_recovered = true;
}

}  // namespace lifelong::io
