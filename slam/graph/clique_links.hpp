// The links the covariance projection (dijkstra.hpp) takes from a graph's clique factors.
// Clique factors are grouped by root: their informations are over the same root-relative
// errors y (pose_graph.hpp), and a sparse GLC (glc.hpp) is a tree of one marginal (an edge
// from the root) and conditionals whose informations are singular each; only their sum is
// definite. A group is inverted as a whole, and each pair of its nodes gets a link: the
// covariance of their relative pose, with the pair's correlation.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slam/graph/pose_graph.hpp"

namespace lifelong::slam {

/// One directed link: the covariance of the relative pose from -> to, in the error
/// coordinates of an edge from -> to (RelativeError, in `to`'s frame).
struct CliqueLink {
  NodeId from = 0, to = 0;
  Eigen::Matrix3d covariance;
};

/// The covariances of the clique groups, kept between projections. A group's information
/// changes only when its factors do, and inverting it is the projection's dearest step on a
/// GLC graph (its singular groups take an eigen decomposition). An entry is reused only for
/// the same information to the bit, so a projection gives the same result with the cache or
/// without it. A group has two entries: alone, and anchored by other groups (CliqueLinks).
class CliqueGroupCache {
 public:
  /// The covariance for `information` of the group rooted at `root` (`anchored` or not);
  /// `invert` computes it when the entry is missing or was for another information.
  template <typename Invert>
  const Eigen::MatrixXd& Covariance(NodeId root, bool anchored, const Eigen::MatrixXd& information,
                                    Invert&& invert) {
    Entry& e = entries_[{root, anchored}];
    e.used = true;
    if (e.information.rows() != information.rows() || e.information != information) {
      e.information = information;
      e.covariance = invert(information);
    }
    return e.covariance;
  }
  /// Drops the entries no projection used since the last call (their roots left or changed).
  void DropUnused();
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    Eigen::MatrixXd information, covariance;
    bool used = false;
  };
  std::map<std::pair<NodeId, bool>, Entry> entries_;
};

/// The links of every clique group, both directions of each pair. A group whose own factors
/// leave a member's y uninformed (a GLC conditional whose tree marginal lies in another
/// group, where the root and that member are two members) is anchored: the other group's
/// link root -> member is added to the member's information, and the group inverted again.
/// `cache` (optional) keeps the groups' covariances for the next call.
std::vector<CliqueLink> CliqueLinks(const PoseGraph& graph, const Values& values,
                                    CliqueGroupCache* cache = nullptr);

}  // namespace lifelong::slam
