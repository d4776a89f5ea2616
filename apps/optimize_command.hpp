// `lifelong optimize`: a g2o or TORO pose graph through the back-end, in the thin program
// (slam and io only).
#pragma once

#include <string>

namespace lifelong::apps {

struct OptimizeArgs {
  std::string graph, out;
  std::string method = "lm";
  std::string solver = "auto";
  bool no_init = false;
};

/// Optimizes args.graph, prints the figures and writes args.out if given. InputError on bad
/// input (an unknown method or solver, an empty graph, a chi2 that overflows).
int OptimizeGraph(const OptimizeArgs& args);

}  // namespace lifelong::apps
