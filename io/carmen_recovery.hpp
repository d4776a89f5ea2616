// Undoing GMapping's correction of a CARMEN log (io/carmen_log.hpp): the pattern that marks a
// corrected log, and the raw odometry rebuilt from it. Internal to io.
#pragma once

#include <string>
#include <vector>

#include "io/carmen_log.hpp"

namespace lifelong::io {

/// FLASER and ODOM messages in file order, for the odometry recovery.
struct Event {
  bool is_flaser = false;
  std::size_t index = 0;  ///< into observations or odometry
  int line = 0;
  Pose2 corrected;  ///< scans: the FLASER's first pose triple
};

/// The GMapping pattern: every scan has an ODOM just before it and an ODOM repeating its
/// corrected pose just after it (the last scan may end the log); the ODOM before carries the
/// scan's stamp, on all but 1 % of the scans (seattle-corrected has one ODOM stamped 0
/// there). `scans` counts the FLASERs, `broken` those without the pattern.
bool LooksCorrected(const std::vector<Event>& ev, const CarmenLog& log, int* scans, int* broken);

/// Rebuilds raw odometry: raw(t) = raw_{k-1} * Between(corrected_{k-1}, ODOM(t)); fills
/// log->corrected_poses. A scan whose ODOM before it is the previous scan's repeat has lost its
/// step: raw_k = raw_{k-1}, marked Observation::odometry_lost. Throws InputError naming `path` and
/// the line of a scan with no ODOM before it.
void RecoverOdometry(const std::vector<Event>& ev, const std::string& path, CarmenLog* log);

}  // namespace lifelong::io
