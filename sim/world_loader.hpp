// Loading worlds from YAML (metres). Format, with every key but `walls` optional:
//   clearance_m: 0.3                       # places and roadmap edges keep this from walls
//   walls:   [{polyline: [[x, y], ...]}, {polygon: [[x, y], ...]}]   # polygon = solid,
//            # no repeated points; a polygon needs 3+ points, an area and no self-crossing
//   doors:   [{name: d1, from: [x, y], to: [x, y], closed_s: [[t0, t1], ...]}]
//   boxes:   [{name: b1, center: [x, y], size: [w, h], yaw_deg: 0,
//              moves: [{t_s: 600, center: [x, y], yaw_deg: 90}]}]
//   places:  [{name: a, at: [x, y]}]
//   roadmap: [[a, b], ...]                 # edges between places, must not cross walls
#pragma once

#include <string>

#include "sim/world.hpp"

namespace lifelong::sim {

/// Throws lifelong::InputError (file, line, field) on any malformed or invalid content,
/// including a key given twice in one map.
World LoadWorld(const std::string& path);
/// The same from YAML text; `name` stands in for the file name in errors.
World LoadWorldFromString(const std::string& yaml, const std::string& name);

}  // namespace lifelong::sim
