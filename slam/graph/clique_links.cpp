#include "slam/graph/clique_links.hpp"

#include <algorithm>
#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "slam/graph/se2.hpp"

namespace lifelong::slam {
namespace {

/// A variance (m^2 or rad^2) past which a direction counts as uninformed: GroupCovariance
/// puts a singular group's free directions at ~1e9.
constexpr double kUninformed = 1e6;

/// The clique factors rooted at one node, and their joint covariance once inverted.
struct Group {
  NodeId root = 0;
  std::vector<NodeId> members;  // nodes other than the root, ascending
  std::vector<const CliqueFactor*> factors;
  Eigen::MatrixXd information;             // over the members' y, 3 rows each
  const Eigen::MatrixXd* sigma = nullptr;  // its inverse (in the cache)

  Eigen::Index At(NodeId id) const {
    return 3 * static_cast<Eigen::Index>(std::lower_bound(members.begin(), members.end(), id) -
                                         members.begin());
  }
  bool Has(NodeId id) const {
    return id == root || std::binary_search(members.begin(), members.end(), id);
  }
  bool Uninformed(NodeId member) const {
    return sigma->block<3, 3>(At(member), At(member)).diagonal().maxCoeff() > kUninformed;
  }
};

/// The covariance of a group's root-relative errors y from their information. A group may be
/// singular alone (GLC conditionals, each rank 3, whose marginal lies in another group): its
/// null directions (eigenvalues under 1e-12 of the largest) come out at 1e9, which the
/// projection cannot pass, and the informative ones exact, so a link along them (between
/// two members) stays usable.
Eigen::MatrixXd GroupCovariance(const Eigen::MatrixXd& information) {
  const Eigen::MatrixXd sym = 0.5 * (information + information.transpose());
  const Eigen::LLT<Eigen::MatrixXd> llt(sym);
  if (llt.info() == Eigen::Success && llt.rcond() > 1e-10) {
    return llt.solve(Eigen::MatrixXd::Identity(sym.rows(), sym.cols()));
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(sym);
  const Eigen::VectorXd& d = eig.eigenvalues();
  const double floor = 1e-12 * std::max(d.maxCoeff(), 0.0);
  Eigen::VectorXd inv(d.size());
  for (Eigen::Index k = 0; k < d.size(); ++k) inv(k) = 1.0 / ((d(k) > floor ? d(k) : 0.0) + 1e-9);
  return eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

/// The groups of the graph's clique factors, with the information of each: the factors'
/// blocks, and the edges from the root to a member (GLC's tree marginal informs y directly).
std::vector<Group> GroupByRoot(const PoseGraph& graph) {
  std::map<NodeId, Group> by_root;
  for (const CliqueFactor& f : graph.cliques()) {
    Group& group = by_root[f.nodes[0]];
    group.root = f.nodes[0];
    group.members.insert(group.members.end(), f.nodes.begin() + 1, f.nodes.end());
    group.factors.push_back(&f);
  }
  for (auto& [root, group] : by_root) {
    std::vector<NodeId>& members = group.members;
    std::sort(members.begin(), members.end());
    members.erase(std::unique(members.begin(), members.end()), members.end());
    const Eigen::Index n = 3 * static_cast<Eigen::Index>(members.size());
    group.information = Eigen::MatrixXd::Zero(n, n);
    for (const CliqueFactor* f : group.factors) {
      for (std::size_t i = 1; i < f->nodes.size(); ++i) {
        for (std::size_t j = 1; j < f->nodes.size(); ++j) {
          group.information.block<3, 3>(group.At(f->nodes[i]), group.At(f->nodes[j])) +=
              f->information.block<3, 3>(3 * static_cast<Eigen::Index>(i - 1),
                                         3 * static_cast<Eigen::Index>(j - 1));
        }
      }
    }
  }
  for (const PoseEdge& e : graph.edges()) {
    const auto it = by_root.find(e.from);
    if (it != by_root.end() && e.to != e.from && it->second.Has(e.to)) {
      it->second.information.block<3, 3>(it->second.At(e.to), it->second.At(e.to)) += e.information;
    }
  }
  std::vector<Group> groups;
  groups.reserve(by_root.size());
  for (auto& [root, group] : by_root) groups.push_back(std::move(group));
  return groups;
}

/// The covariance of the relative pose a -> b, both in the group (root or member).
/// y_j = t2v(Z_j^-1 X_r^-1 X_j) is the error of the relative pose r -> j in j's frame, so
/// r -> j is the block Sigma_jj, and j -> r, whose error is -Ad(Z_j) y_j in r's frame,
/// Ad(Z_j) Sigma_jj Ad(Z_j)^T; the error of i -> j is d_ij = y_j - Ad(Z_ij^-1) y_i
/// (Z_ij = X_i^-1 X_j), whose covariance takes the pair's correlation.
Eigen::Matrix3d RelativeCovariance(const Group& g, const Values& values, NodeId a, NodeId b) {
  const auto block = [&](NodeId i, NodeId j) -> Eigen::Matrix3d {
    return g.sigma->block<3, 3>(g.At(i), g.At(j));
  };
  if (a == g.root) return block(b, b);
  const Pose2& Xa = values.at(a);
  const Pose2& Xb = values.at(b);
  if (b == g.root) {
    const Eigen::Matrix3d back = Adjoint(Between(Xb, Xa));
    return back * block(a, a) * back.transpose();
  }
  const Eigen::Matrix3d A = Adjoint(Between(Xa, Xb).Inverse());
  return block(b, b) - block(b, a) * A.transpose() - A * block(a, b) +
         A * block(a, a) * A.transpose();
}

/// The information another group gives to the uninformed members of `g`: for member j, the
/// most certain link root -> j of a group holding both (where, for GLC, the tree marginal
/// that g's conditionals lack lies). Zero where none informs it.
Eigen::MatrixXd Anchor(const Group& g, std::size_t self, const std::vector<Group>& groups,
                       const std::map<NodeId, std::vector<std::size_t>>& holding,
                       const Values& values) {
  Eigen::MatrixXd anchor = Eigen::MatrixXd::Zero(g.information.rows(), g.information.cols());
  const auto of_root = holding.find(g.root);
  if (of_root == holding.end()) return anchor;
  for (NodeId j : g.members) {
    if (!g.Uninformed(j)) continue;
    Eigen::Matrix3d best;
    double best_trace = std::numeric_limits<double>::infinity();
    for (std::size_t h : of_root->second) {
      if (h == self || !groups[h].Has(j)) continue;
      const Eigen::Matrix3d c = RelativeCovariance(groups[h], values, g.root, j);
      if (c.diagonal().maxCoeff() < kUninformed && c.trace() < best_trace) {
        best = c;
        best_trace = c.trace();
      }
    }
    if (best_trace < kUninformed) anchor.block<3, 3>(g.At(j), g.At(j)) = RegularizedInverse(best);
  }
  return anchor;
}

}  // namespace

void CliqueGroupCache::DropUnused() {
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (!it->second.used) {
      it = entries_.erase(it);
    } else {
      it->second.used = false;
      ++it;
    }
  }
}

std::vector<CliqueLink> CliqueLinks(const PoseGraph& graph, const Values& values,
                                    CliqueGroupCache* cache) {
  CliqueGroupCache local;
  CliqueGroupCache& store = cache ? *cache : local;
  std::vector<Group> groups = GroupByRoot(graph);
  std::map<NodeId, std::vector<std::size_t>> holding;  // the groups each node is in
  for (std::size_t k = 0; k < groups.size(); ++k) {
    groups[k].sigma =
        &store.Covariance(groups[k].root, false, groups[k].information, GroupCovariance);
    holding[groups[k].root].push_back(k);
    for (NodeId m : groups[k].members) holding[m].push_back(k);
  }
  // One anchoring pass, from the groups as they stand alone (an anchor is not passed on).
  std::vector<const Eigen::MatrixXd*> anchored(groups.size(), nullptr);
  for (std::size_t k = 0; k < groups.size(); ++k) {
    const Eigen::MatrixXd anchor = Anchor(groups[k], k, groups, holding, values);
    if (anchor.isZero(0.0)) continue;
    anchored[k] =
        &store.Covariance(groups[k].root, true, groups[k].information + anchor, GroupCovariance);
  }
  std::vector<CliqueLink> links;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    Group& g = groups[k];
    if (anchored[k]) g.sigma = anchored[k];
    for (std::size_t j = 0; j < g.members.size(); ++j) {
      const NodeId m = g.members[j];
      links.push_back({g.root, m, RelativeCovariance(g, values, g.root, m)});
      links.push_back({m, g.root, RelativeCovariance(g, values, m, g.root)});
      for (std::size_t i = 0; i < j; ++i) {
        links.push_back({g.members[i], m, RelativeCovariance(g, values, g.members[i], m)});
        links.push_back({m, g.members[i], RelativeCovariance(g, values, m, g.members[i])});
      }
    }
  }
  if (cache) cache->DropUnused();
  return links;
}

}  // namespace lifelong::slam
