// What built this program, for the report's provenance: the project version (CMake) and
// the `git describe --always --dirty` of the checkout at build time ("unknown" when the
// sources were not a git checkout). Refreshed at every build by cmake/WriteBuildInfo.cmake.
#pragma once

#include <string>

namespace lifelong::eval {

struct BuildInfo {
  std::string version;  ///< e.g. "0.1.0"
  std::string commit;   ///< e.g. "523ae7b-dirty", or "unknown"
};

BuildInfo GetBuildInfo();

}  // namespace lifelong::eval
