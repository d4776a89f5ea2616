// TUM RGB-D benchmark trajectories (Sturm et al. 2012): `stamp x y z qx qy qz qw` per line,
// the pose of the robot in the world frame. Planar poses: z = 0, rotation about z only,
// q = (0, 0, sin(yaw/2), cos(yaw/2)).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "types/stamped_pose.hpp"

namespace lifelong::io {

/// Writes stamps and positions with 6 decimals, quaternions with 9 (locale-independent),
/// atomically (io/atomic_file.hpp). Throws InputError when unwritable.
void WriteTum(const std::string& path, const std::vector<StampedPose>& poses);

/// Reads a TUM file back, converting each quaternion to yaw (roll and pitch ignored).
/// `#` comments and blank lines are skipped; malformed lines throw InputError.
std::vector<StampedPose> ReadTum(const std::string& path);
/// Same, from a stream; `name` stands for the file in error messages.
std::vector<StampedPose> ParseTum(std::istream& in, const std::string& name);

/// A reference trajectory in either of the two plain formats, told apart by the first data
/// line: 8 fields (TUM, as above) or 4 (`t x y theta`, theta in radians). `#` comments and
/// blank lines are skipped. Throws InputError at the line that breaks the format, for an
/// empty file, or for stamps that do not increase.
std::vector<StampedPose> ReadTrajectory(const std::string& path);

}  // namespace lifelong::io
