// Relations files of Kümmerle et al. 2009 ("On measuring the accuracy of SLAM
// algorithms"): one line `t1 t2 x y z roll pitch yaw` per ground-truth relative pose of
// the robot at t2 in the frame of the robot at t1. Planar use keeps x, y and yaw.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "types/relation.hpp"

namespace lifelong::io {

/// s; intel.relations stamps are absolute: relation time = log time + this offset.
constexpr double kIntelRelationsTimeOffsetS = 976052857.337284;

/// Reads a relations file and subtracts `time_offset_s` from both stamps so they are log
/// times. Blank lines and `#` comments are skipped; anything else malformed throws
/// lifelong::InputError with the line number and field.
std::vector<Relation> ReadRelations(const std::string& path, double time_offset_s);
/// Same, from a stream; `name` stands for the file in error messages.
std::vector<Relation> ParseRelations(std::istream& in, const std::string& name,
                                     double time_offset_s);

}  // namespace lifelong::io
