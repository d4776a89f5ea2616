#include "slam/sparsify/set_marginal.hpp"

#include <algorithm>
#include <map>
#include <numeric>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

#include "slam/backend/clique_algebra.hpp"
#include "slam/marginal/marginalization.hpp"

namespace lifelong::slam {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Union-find over positions 0..n-1.
struct Sets {
  std::vector<std::size_t> parent;
  explicit Sets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::size_t Find(std::size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void Join(std::size_t a, std::size_t b) { parent[Find(a)] = Find(b); }
};

/// The factors' H and g, scattered into triplets over `position` (node -> row block).
struct Assembly {
  const std::map<NodeId, std::size_t>& position;
  std::vector<Eigen::Triplet<double, int>> triplets;
  VectorXd g;
  double chi2 = 0.0;

  void Add(const std::vector<NodeId>& nodes, const MatrixXd& h, const VectorXd& gf) {
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      const auto ra = static_cast<int>(3 * position.at(nodes[a]));
      g.segment<3>(ra) += gf.segment<3>(clique::Block(a));
      for (std::size_t b = 0; b < nodes.size(); ++b) {
        const auto rb = static_cast<int>(3 * position.at(nodes[b]));
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            triplets.emplace_back(ra + i, rb + j, h(clique::Block(a) + i, clique::Block(b) + j));
          }
        }
      }
    }
  }
  void AddEdge(const PoseEdge& e, const Values& values) {
    const std::vector<NodeId> nodes{e.from, e.to};
    const LocalSystem s = LinearizeEdges(nodes, values, {e});
    Add(nodes, s.H, s.g);
    chi2 += s.chi2;
  }
  void AddClique(const CliqueFactor& c, const Values& values) {
    MatrixXd h = MatrixXd::Zero(clique::Block(c.nodes.size()), clique::Block(c.nodes.size()));
    VectorXd gf = VectorXd::Zero(h.rows());
    chi2 += AddCliqueLinearized(c, values, c.nodes, &h, &gf);
    Add(c.nodes, h, gf);
  }
};

}  // namespace

std::vector<std::vector<NodeId>> ConnectedSets(const PoseGraph& graph,
                                               const std::vector<NodeId>& remove) {
  const auto pos = [&](NodeId n) {
    return static_cast<std::size_t>(std::lower_bound(remove.begin(), remove.end(), n) -
                                    remove.begin());
  };
  const auto removed = [&](NodeId n) {
    return std::binary_search(remove.begin(), remove.end(), n);
  };
  Sets sets(remove.size());
  for (NodeId n : remove) {
    for (NodeId m : graph.Neighbours(n)) {
      if (removed(m)) sets.Join(pos(n), pos(m));
    }
  }
  std::map<std::size_t, std::vector<NodeId>> by_root;
  std::vector<std::size_t> order;  // roots by their first (smallest) member
  for (std::size_t i = 0; i < remove.size(); ++i) {
    auto& members = by_root[sets.Find(i)];
    if (members.empty()) order.push_back(sets.Find(i));
    members.push_back(remove[i]);
  }
  std::vector<std::vector<NodeId>> out;
  out.reserve(order.size());
  for (std::size_t root : order) out.push_back(std::move(by_root[root]));
  return out;
}

std::optional<SetMarginal> MarginalizeSet(const PoseGraph& graph, const Values& values,
                                          const std::vector<NodeId>& set, bool within_boundary) {
  const auto in_set = [&](NodeId n) { return std::binary_search(set.begin(), set.end(), n); };
  SetMarginal out;
  for (NodeId n : set) {
    for (NodeId m : graph.Neighbours(n)) {
      if (!in_set(m)) out.boundary.push_back(m);
    }
  }
  std::sort(out.boundary.begin(), out.boundary.end());
  out.boundary.erase(std::unique(out.boundary.begin(), out.boundary.end()), out.boundary.end());
  if (out.boundary.size() < 2) return std::nullopt;

  // Rows: the set's blocks first, then the boundary's.
  std::map<NodeId, std::size_t> position;
  for (NodeId n : set) position.emplace(n, position.size());
  for (NodeId n : out.boundary) position.emplace(n, position.size());
  const auto ns = static_cast<Eigen::Index>(3 * set.size());
  const auto nb = static_cast<Eigen::Index>(3 * out.boundary.size());
  Assembly assembly{position, {}, VectorXd::Zero(ns + nb)};

  // Every factor touching the set once (a factor may touch several of its nodes).
  std::vector<std::size_t> edges, cliques;
  for (NodeId n : set) {
    const auto e = graph.EdgesOf(n);
    const auto c = graph.CliquesOf(n);
    edges.insert(edges.end(), e.begin(), e.end());
    cliques.insert(cliques.end(), c.begin(), c.end());
  }
  for (auto* v : {&edges, &cliques}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  for (std::size_t e : edges) assembly.AddEdge(graph.edges()[e], values);
  for (std::size_t c : cliques) assembly.AddClique(graph.cliques()[c], values);
  if (within_boundary) {
    for (const PoseEdge& e : graph.EdgesWithin(out.boundary)) assembly.AddEdge(e, values);
    for (const CliqueFactor& c : graph.CliquesWithin(out.boundary)) {
      assembly.AddClique(c, values);
    }
  }
  Sparse H(static_cast<int>(ns + nb), static_cast<int>(ns + nb));
  H.setFromTriplets(assembly.triplets.begin(), assembly.triplets.end());
  std::vector<Eigen::Triplet<double, int>>().swap(assembly.triplets);

  // Lambda_B = H_BB - H_BS X, X = H_SS^-1 [H_SB | g_S] (one factorization, many right sides).
  const Sparse h_ss = H.topLeftCorner(ns, ns);
  const Sparse h_bs = H.bottomLeftCorner(nb, ns);
  Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> llt(h_ss);
  if (llt.info() != Eigen::Success) return std::nullopt;
  MatrixXd rhs(ns, nb + 1);
  rhs.leftCols(nb) = MatrixXd(h_bs.transpose());
  rhs.col(nb) = assembly.g.head(ns);
  const MatrixXd x = llt.solve(rhs);
  if (llt.info() != Eigen::Success || !x.allFinite()) return std::nullopt;
  const MatrixXd lambda = MatrixXd(H.bottomRightCorner(nb, nb)) - h_bs * x.leftCols(nb);
  out.marginal.lambda_N = 0.5 * (lambda + lambda.transpose());
  out.marginal.g_N = assembly.g.tail(nb) - h_bs * x.col(nb);
  out.marginal.chi2 = assembly.chi2;
  return out;
}

void ApplySetReplacement(PoseGraph* graph, const std::vector<NodeId>& set, const Replacement& r) {
  if (r.absorb_edges_within) graph->RemoveEdgesWithin(r.neighbours);
  if (r.absorb_cliques_within) graph->RemoveCliquesWithin(r.neighbours);
  for (NodeId n : set) graph->RemoveNode(n);
  for (const PoseEdge& e : r.edges) graph->AddEdge(e);
  for (const CliqueFactor& c : r.cliques) graph->AddClique(c);
}

}  // namespace lifelong::slam
