// `lifelong sparsify`: the offline sparsification protocol on a g2o/TORO pose graph
// (slam/sparsify/offline_sparsify.hpp, slam/marginal/global_kl.hpp); slam + io only, like
// `optimize`.
#pragma once

#include <optional>
#include <string>

namespace lifelong::apps {

struct SparsifyArgs {
  std::string graph;                  ///< g2o or TORO input
  std::string out;                    ///< OUT.g2o; empty: write nothing
  std::string method;                 ///< a slam::SparsifierNames() entry
  std::optional<double> keep_share;   ///< keep this share of the nodes, evenly by id
  std::string remove;                 ///< or: a file of node ids to remove
  bool zero_residual = false;         ///< new factors' measurements at x*: --means estimate
  std::string means = "gradient";     ///< estimate | gradient | marginal_mean
  bool no_blanket = false;            ///< replace only the factors at k, keep those among N
  std::string nfr_chords = "joined";  ///< nfr-subgraph's extra pairs: joined | mi
};

/// Runs the protocol and prints one JSON object on stdout; throws InputError on bad input.
int Sparsify(const SparsifyArgs& args);

}  // namespace lifelong::apps
