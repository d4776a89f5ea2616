#include "eval/report/build_info.hpp"

#include "lifelong_build_info.hpp"  // generated into the build tree

namespace lifelong::eval {

BuildInfo GetBuildInfo() { return {LIFELONG_VERSION, LIFELONG_COMMIT}; }

}  // namespace lifelong::eval
