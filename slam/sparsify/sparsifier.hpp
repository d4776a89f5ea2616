// Sparsifiers: what replaces a removed node's elimination clique (DESIGN.md "Methods as
// parts"). Given the graph, the estimate and a node k, a sparsifier returns the factors that
// replace k (and, for blanket methods, the factors among k's neighbours N), plus what it
// lost. One class per method, each in its own file, chosen by name (MakeSparsifier):
//   naive      star of composed edges through k (marginalization.hpp, kNaive)
//   exact      one dense root-relative clique over N (kExact, the seed's fill-in)
//   chow-liu   Chow-Liu tree of relative-pose edges (kChowLiu, the seed's contribution)
//   glc-dense  GLC (Carlevaris-Bianco, Kaess & Eustice, T-RO 2014): the exact marginal as one
//              root-shifted linear factor, keeping only its informative directions (glc.hpp)
//   glc        GLC with the Chow-Liu tree taken in the root-shifted parametrization (glc.hpp)
//   nfr-tree   NFR (Mazuran et al., IJRR 2016): relative-pose edges on the Chow-Liu tree with
//              the KL-optimal informations (closed form; nfr.hpp)
//   nfr-subgraph  NFR on the tree plus more pairs of N (joined by edges before the removal,
//              or by mutual information; within an edge budget), by projected Newton (nfr.hpp)
//
// Means. Every factor is linearized at the current estimate x*. The wrapped methods take
// their measurements from x* (zero residual), as the mapper does. With
// SparsifierConfig::means kGradient the measurements are moved (PreserveGradient) so that
// the replacement's gradient at x* equals that of the exact marginal: then an exact method
// leaves the optimum where it was, and what a method loses is its information alone. With
// kMarginalMean they are moved so that the replacement's minimum is the exact marginal's mean
// (the KL divergence's mean term vanishes); for an exact method both agree.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "slam/graph/pose_graph.hpp"
#include "slam/marginal/marginalization.hpp"

namespace lifelong::slam {

/// Candidate pairs for nfr-subgraph's edges beyond the Chow-Liu tree.
enum class NfrChords {
  kJoined,             ///< pairs of N joined by pose edges before the removal
  kMutualInformation,  ///< every pair of N (Mazuran et al.'s code: the next pairs by weight)
};

/// Where the new factors' measurements put their minimum (see "Means" above).
enum class FactorMeans {
  kEstimate,      ///< at x*: zero residual, the seed's rule
  kGradient,      ///< moved so their gradient at x* is the exact marginal's (PreserveGradient)
  kMarginalMean,  ///< moved so their minimum is the exact marginal's mean x* - Lambda^+ g
};

struct SparsifierConfig {
  /// kBlanket: the factors among N (pose edges, and clique factors for glc) are folded into
  /// the clique's Gaussian and replaced too (chow-liu and glc only; the mapper's default).
  BlanketPolicy blanket = BlanketPolicy::kBlanket;
  /// Where the new factors' measurements put their minimum.
  FactorMeans means = FactorMeans::kEstimate;
  /// GLC: eigenvalues below this fraction of the largest are dropped (informative directions).
  double eigen_tolerance = 1e-10;
  /// nfr-subgraph: at most floor(nfr_chord_ratio * (m - 1)) edges beyond the tree per clique
  /// of m nodes (1: at most 2 (m - 1) edges in all; 0: the tree alone).
  double nfr_chord_ratio = 1.0;
  /// nfr-subgraph: which pairs beyond the tree may get an edge (the strongest first by the
  /// chow-liu pair weight).
  NfrChords nfr_chords = NfrChords::kJoined;
};

/// What replaces node k: apply with ApplyReplacement.
struct Replacement {
  std::vector<NodeId> neighbours;      ///< N, ascending
  std::vector<PoseEdge> edges;         ///< new relative-pose factors (kind kMarginal)
  std::vector<CliqueFactor> cliques;   ///< new linear factors (root-relative, pose_graph.hpp)
  bool absorb_edges_within = false;    ///< remove the pose edges among N first (blanket)
  bool absorb_cliques_within = false;  ///< remove the clique factors among N first (blanket)
  /// nats, KL(exact clique marginal || replacement) over N in the gauge of N[0]; 0 for exact
  /// methods, +inf when the replacement leaves N disconnected.
  double kl_divergence = 0.0;
  bool regularized = false;  ///< a near-singular matrix needed a documented diagonal shift
  /// Pairs for the gamma index: each edge once, each clique over m nodes m(m-1)/2.
  std::size_t Pairs() const;
};

class Sparsifier {
 public:
  virtual ~Sparsifier() = default;
  virtual std::string Name() const = 0;
  /// Node k must exist in graph and values, with all its neighbours.
  virtual Replacement Replace(const PoseGraph& graph, const Values& values, NodeId k) const = 0;
  /// Whether its factors are the Chow-Liu tree's pose edges, so that the mapper's edge budget
  /// (Chow-Liu trees of the densest blankets, PruningConfig::max_edges_per_node) keeps the
  /// graph of the same kind.
  virtual bool LeavesTrees() const { return false; }
  /// Whether ReplaceSet can replace sets (then SparsifyOffline hands it each connected set).
  virtual bool ReplacesSets() const { return false; }
  /// A method whose factors are the exact marginal (exact, glc-dense) does not depend on the
  /// order of elimination, so it may replace a connected set of removed nodes (ascending) at
  /// once, with what removing them one at a time would leave (set_marginal.hpp); r's
  /// neighbours are then the set's boundary. nullopt: remove them one at a time.
  virtual std::optional<Replacement> ReplaceSet(const PoseGraph& graph, const Values& values,
                                                const std::vector<NodeId>& set) const {
    (void)graph, (void)values, (void)set;
    return std::nullopt;
  }
};

/// The sparsifier called `name`, or nullptr when no method has that name.
std::unique_ptr<Sparsifier> MakeSparsifier(const std::string& name,
                                           const SparsifierConfig& config = {});
/// Every known name, in the registry's order.
std::vector<std::string> SparsifierNames();

/// Removes k (and the factors among N that r absorbed), then adds r's factors.
void ApplyReplacement(PoseGraph* graph, NodeId k, const Replacement& r);

// ---- Shared by the method files (public for tests). ----

/// The elimination clique of k linearized at `values`: H and gradient g = J^T Omega e over
/// [x_k, x_N] (block i + 1 is neighbours[i]); optionally with the factors among N.
struct LocalSystem {
  std::vector<NodeId> neighbours;
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  double chi2 = 0.0;  ///< sum of e^T Omega e over the factors linearized
};
LocalSystem LinearizeClique(const PoseGraph& graph, const Values& values, NodeId k,
                            bool edges_within, bool cliques_within);

/// Eliminates x_k from a LocalSystem: Lambda_N = H_NN - H_Nk H_kk^+ H_kN and
/// g_N - H_Nk H_kk^+ g_k (pseudo-inverse: exact for PSD H).
void EliminateFirstBlock(const LocalSystem& system, Eigen::MatrixXd* lambda_N,
                         Eigen::VectorXd* g_N);

/// Moves the measurements of `edges` and `cliques` (over `nodes`, ascending) so that their
/// Hessian at `values` is unchanged and their gradient equals `g_N` (when g_N lies in the
/// range of that Hessian; else its projection): residual e = J z with z = Lambda_q^+ g_N,
/// each 3-block rotated so the error Jacobian keeps its value (closed form, no iteration).
/// None of g_N is kept (the factors stay as given) when z would take a factor's heading
/// residual past what a measurement can carry (about pi). With `lambda_N` (the exact
/// marginal's information): z = lambda_N^+ g_N - Lambda_q^+ g_q instead, so the factors'
/// minimum (to first order) moves to the marginal's mean rather than their gradient to g_N.
/// With lambda_N, none is kept either when the moved factors would hold more error at
/// `values` than `chi2_replaced`, that of the factors they replace, plus one per coordinate
/// of g_N: the exact marginal never holds more than that chi2 (g_N^T Lambda_N^+ g_N), but a
/// sparsified one whose information is stiff where Lambda_N is nearly free can, and then
/// pulls far harder than g_N (a GLC tree after a 9-neighbour elimination held chi2 5e8, and
/// the back-end diverged). Without lambda_N the pull at `values` is g_N itself.
void PreserveGradient(const std::vector<NodeId>& nodes, const Values& values,
                      const Eigen::VectorXd& g_N, std::vector<PoseEdge>* edges,
                      std::vector<CliqueFactor>* cliques, const Eigen::MatrixXd* lambda_N = nullptr,
                      double chi2_replaced = std::numeric_limits<double>::infinity());

/// Moves the factors as `means` asks, given the exact marginal (lambda_N, g_N) they replace:
/// nothing for kEstimate, PreserveGradient for kGradient, and with lambda_N for kMarginalMean.
/// `chi2_replaced`: the error the replaced factors held (LocalSystem::chi2).
void MoveMeans(FactorMeans means, const std::vector<NodeId>& nodes, const Values& values,
               const Eigen::MatrixXd& lambda_N, const Eigen::VectorXd& g_N, double chi2_replaced,
               std::vector<PoseEdge>* edges, std::vector<CliqueFactor>* cliques);

/// e^T Lambda e of a clique factor, e its stacked root-relative errors at `values`.
double CliqueChi2(const CliqueFactor& clique, const Values& values);
/// The summed e^T Omega e of `edges` and `cliques` at `values`.
double FactorsChi2(const Values& values, const std::vector<PoseEdge>& edges,
                   const std::vector<CliqueFactor>& cliques);

/// Hessian J^T Omega J and gradient J^T Omega e of `edges` over `nodes` (ascending) at
/// `values` (LocalSystem::neighbours is left empty).
LocalSystem LinearizeEdges(const std::vector<NodeId>& nodes, const Values& values,
                           const std::vector<PoseEdge>& edges);

/// Hessian of `edges` and `cliques` over `nodes` (ascending) at `values`.
Eigen::MatrixXd FactorsHessian(const std::vector<NodeId>& nodes, const Values& values,
                               const std::vector<PoseEdge>& edges,
                               const std::vector<CliqueFactor>& cliques);

/// The exact marginal of k's clique, for the methods that build their factors from it
/// (glc-dense, glc): LinearizeClique with the factors among N when config.blanket is
/// kBlanket (they are replaced too), then EliminateFirstBlock. Sets r's neighbours and
/// absorb flags; false when k is a leaf (fewer than two neighbours: it simply drops out).
struct CliqueMarginal {
  Eigen::MatrixXd lambda_N;
  Eigen::VectorXd g_N;
  double chi2 = 0.0;  ///< of the factors it replaces
};
bool MarginalToReplace(const SparsifierConfig& config, const PoseGraph& graph, const Values& values,
                       NodeId k, Replacement* r, CliqueMarginal* m);
/// r's factors become `edges` and `cliques`, with r.kl_divergence their InformativeKl
/// (glc.hpp) against m.lambda_N.
void SetFactors(const SparsifierConfig& config, const Values& values, const CliqueMarginal& m,
                std::vector<PoseEdge> edges, std::vector<CliqueFactor> cliques, Replacement* r);

/// The wrapped methods' result as a Replacement (factors unchanged, byte for byte).
Replacement FromMarginalization(const MarginalizationResult& m);
/// Unless config.means is kEstimate: PreserveGradient with the exact marginal of the clique
/// as LinearizeClique(..., edges_within, cliques_within) sees it (its information too, for
/// kMarginalMean).
void KeepGradientIfAsked(const SparsifierConfig& config, const PoseGraph& graph,
                         const Values& values, NodeId k, bool edges_within, bool cliques_within,
                         Replacement* r);

// ---- One factory per method file. ----
std::unique_ptr<Sparsifier> MakeNaiveSparsifier(const SparsifierConfig& config);
std::unique_ptr<Sparsifier> MakeExactSparsifier(const SparsifierConfig& config);
std::unique_ptr<Sparsifier> MakeChowLiuSparsifier(const SparsifierConfig& config);
std::unique_ptr<Sparsifier> MakeGlcDenseSparsifier(const SparsifierConfig& config);
std::unique_ptr<Sparsifier> MakeGlcSparsifier(const SparsifierConfig& config);
std::unique_ptr<Sparsifier> MakeNfrTreeSparsifier(const SparsifierConfig& config);
std::unique_ptr<Sparsifier> MakeNfrSubgraphSparsifier(const SparsifierConfig& config);

}  // namespace lifelong::slam
