// Wall segments as text: one `x0 y0 x1 y1` line (metres, world frame) per segment, '#'
// comments. A run's truth/walls.tsv and a simulated log's LOG-stem.truth.walls.tsv hold the
// true walls in this form, so that `lifelong score` measures a map against the same
// segments a run does.
#pragma once

#include <string>
#include <vector>

#include "types/segment.hpp"

namespace lifelong::io {

/// Writes atomically, with a comment line naming the columns.
void WriteSegments(const std::string& path, const std::vector<Segment>& segments);
/// Throws InputError naming the file and line on a missing file or a malformed line.
std::vector<Segment> ReadSegments(const std::string& path);

}  // namespace lifelong::io
