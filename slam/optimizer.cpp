#include "slam/optimizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include <cholmod.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include "slam/se2.hpp"

namespace lifelong::slam {
namespace {

constexpr int kNoBlock = -1;

// ---------------------------------------------------------------------------------------
// Robust kernels on s = e^T Omega e (header comment): cost rho(s) and IRLS weight rho'(s).
struct KernelValue {
  double cost;
  double weight;
};

KernelValue ApplyKernel(double s, bool robust, const OptimizerParams& params) {
  const double d2 = params.robust_delta * params.robust_delta;
  if (!robust || params.robust_kernel == RobustKernel::kNone) return {s, 1.0};
  if (params.robust_kernel == RobustKernel::kHuber) {
    if (s <= d2) return {s, 1.0};
    const double r = std::sqrt(s);
    return {2.0 * params.robust_delta * r - d2, params.robust_delta / r};
  }
  return {d2 * std::log1p(s / d2), 1.0 / (1.0 + s / d2)};  // Cauchy
}

// ---------------------------------------------------------------------------------------
// Problem layout: dense node indices, column blocks and the position of every 3x3 block of
// H inside the upper-triangular CSC value array (H_ab with a <= b is stored in block
// column b; `rank` is a's position among the row blocks of that column, the diagonal last).
struct EdgeSlot {
  const PoseEdge* edge;
  int i, j;  // dense node indices
  int rank_ii, rank_jj, rank_ij;
};

struct CliqueSlot {
  const CliqueFactor* clique;
  std::vector<int> nodes;  // dense node indices, nodes[0] = root
  std::vector<int> ranks;  // for each pair (u <= v) of clique members, row-major upper
};

struct Layout {
  std::vector<Pose2*> poses;  // per dense node
  std::vector<int> block;     // per dense node: column block or kNoBlock
  std::vector<EdgeSlot> edges;
  std::vector<CliqueSlot> cliques;
  std::vector<std::vector<int>> rows_of_col;  // per block column b: row blocks a < b
  int num_blocks = 0;
};

int Rank(const Layout& layout, int a, int b) {
  if (a == kNoBlock || b == kNoBlock) return -1;
  if (a > b) std::swap(a, b);
  const std::vector<int>& rows = layout.rows_of_col[static_cast<std::size_t>(b)];
  if (a == b) return static_cast<int>(rows.size());
  return static_cast<int>(std::lower_bound(rows.begin(), rows.end(), a) - rows.begin());
}

void AddPair(Layout* layout, int node_u, int node_v) {
  int a = layout->block[static_cast<std::size_t>(node_u)];
  int b = layout->block[static_cast<std::size_t>(node_v)];
  if (a == kNoBlock || b == kNoBlock || a == b) return;
  if (a > b) std::swap(a, b);
  layout->rows_of_col[static_cast<std::size_t>(b)].push_back(a);
}

// Dense node indices (ascending ids), anchor and factor-less nodes without columns.
void AssignBlocks(const PoseGraph& graph, Values* values, NodeId anchor, Layout* layout) {
  const std::vector<NodeId> ids = graph.NodeIds();
  layout->poses.resize(ids.size());
  layout->block.assign(ids.size(), kNoBlock);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    auto it = values->find(ids[k]);
    if (it == values->end()) {
      throw std::invalid_argument("Optimize: no value for node " + std::to_string(ids[k]));
    }
    layout->poses[k] = &it->second;
    if (ids[k] != anchor && !graph.Neighbours(ids[k]).empty()) {
      layout->block[k] = layout->num_blocks++;
    }
  }
}

int DenseIndex(const std::vector<NodeId>& ids, NodeId id) {
  return static_cast<int>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
}

Layout BuildLayout(const PoseGraph& graph, Values* values, NodeId anchor) {
  Layout layout;
  AssignBlocks(graph, values, anchor, &layout);
  const std::vector<NodeId> ids = graph.NodeIds();
  layout.rows_of_col.resize(static_cast<std::size_t>(layout.num_blocks));
  for (const PoseEdge& e : graph.edges()) {
    EdgeSlot slot{&e, DenseIndex(ids, e.from), DenseIndex(ids, e.to), -1, -1, -1};
    AddPair(&layout, slot.i, slot.j);
    layout.edges.push_back(slot);
  }
  for (const CliqueFactor& c : graph.cliques()) {
    CliqueSlot slot{&c, {}, {}};
    for (NodeId n : c.nodes) slot.nodes.push_back(DenseIndex(ids, n));
    for (std::size_t u = 0; u < slot.nodes.size(); ++u) {
      for (std::size_t v = u + 1; v < slot.nodes.size(); ++v) {
        AddPair(&layout, slot.nodes[u], slot.nodes[v]);
      }
    }
    layout.cliques.push_back(std::move(slot));
  }
  for (auto& rows : layout.rows_of_col) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
  const auto& blk = layout.block;
  for (EdgeSlot& s : layout.edges) {
    const int a = blk[static_cast<std::size_t>(s.i)], b = blk[static_cast<std::size_t>(s.j)];
    s.rank_ii = Rank(layout, a, a);
    s.rank_jj = Rank(layout, b, b);
    s.rank_ij = Rank(layout, a, b);
  }
  for (CliqueSlot& s : layout.cliques) {
    for (std::size_t u = 0; u < s.nodes.size(); ++u) {
      for (std::size_t v = u; v < s.nodes.size(); ++v) {
        s.ranks.push_back(Rank(layout, blk[static_cast<std::size_t>(s.nodes[u])],
                               blk[static_cast<std::size_t>(s.nodes[v])]));
      }
    }
  }
  return layout;
}

// ---------------------------------------------------------------------------------------
// CHOLMOD workspace (RAII): the upper-triangular pattern of H, its analysis, the factor.
class Cholmod {
 public:
  Cholmod(const Layout& layout, LinearSolver solver) {
    cholmod_start(&common_);
    common_.print = 0;  // library code never prints
    // CHOLMOD picks simplicial or supernodal by the factor's density (supernodal wins on
    // lattice-like graphs such as many passes through one corridor, simplicial on sparse
    // ones) and tries METIS after AMD when AMD's fill is poor (docs/bench/backend.md).
    switch (solver) {
      case LinearSolver::kSimplicial:
        common_.supernodal = CHOLMOD_SIMPLICIAL;
        break;
      case LinearSolver::kSupernodal:
        common_.supernodal = CHOLMOD_SUPERNODAL;
        break;
      case LinearSolver::kAuto:
        common_.supernodal = CHOLMOD_AUTO;
        break;
    }
    const std::size_t n = 3 * static_cast<std::size_t>(layout.num_blocks);
    std::size_t nnz = 0;
    for (const auto& rows : layout.rows_of_col) nnz += 9 * rows.size() + 6;
    A_ = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &common_);
    b_ = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &common_);
    int* p = static_cast<int*>(A_->p);
    int* rows_out = static_cast<int*>(A_->i);
    int pos = 0;
    for (std::size_t b = 0; b < layout.rows_of_col.size(); ++b) {
      for (int c = 0; c < 3; ++c) {
        p[3 * b + static_cast<std::size_t>(c)] = pos;
        for (int a : layout.rows_of_col[b]) {
          for (int r = 0; r < 3; ++r) rows_out[pos++] = 3 * a + r;
        }
        for (int r = 0; r <= c; ++r) rows_out[pos++] = static_cast<int>(3 * b) + r;
      }
    }
    p[n] = pos;
    L_ = cholmod_analyze(A_, &common_);
  }
  ~Cholmod() {
    cholmod_free_factor(&L_, &common_);
    cholmod_free_sparse(&A_, &common_);
    cholmod_free_dense(&b_, &common_);
    cholmod_finish(&common_);
  }
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;

  std::size_t Nnz() const { return static_cast<int*>(A_->p)[A_->ncol]; }
  const int* ColPtr() const { return static_cast<const int*>(A_->p); }

  /// Solves (H + lambda D) dx = rhs, D = diag(d); false when not positive definite.
  bool Solve(const std::vector<double>& h, double lambda, const Eigen::VectorXd& d,
             const Eigen::VectorXd& rhs, Eigen::VectorXd* dx) {
    double* x = static_cast<double*>(A_->x);
    std::memcpy(x, h.data(), h.size() * sizeof(double));
    const int* p = ColPtr();
    for (std::size_t j = 0; j < A_->ncol; ++j) {
      x[p[j + 1] - 1] += lambda * d[static_cast<Eigen::Index>(j)];
    }
    cholmod_factorize(A_, L_, &common_);
    if (common_.status != CHOLMOD_OK || L_->minor < L_->n) return false;
    std::memcpy(b_->x, rhs.data(), static_cast<std::size_t>(rhs.size()) * sizeof(double));
    cholmod_dense* sol = cholmod_solve(CHOLMOD_A, L_, b_, &common_);
    if (sol == nullptr) return false;
    *dx = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(sol->x), rhs.size());
    cholmod_free_dense(&sol, &common_);
    return dx->allFinite();
  }

 private:
  cholmod_common common_{};
  cholmod_sparse* A_ = nullptr;
  cholmod_factor* L_ = nullptr;
  cholmod_dense* b_ = nullptr;
};

// ---------------------------------------------------------------------------------------
// Linearization: H (CSC values) and g = J^T W Omega e, straight from the factor Jacobians.
class System {
 public:
  System(const Layout& layout, const int* colptr, std::size_t nnz)
      : layout_(layout), p_(colptr), h_(nnz), g_(3 * layout.num_blocks) {}

  const std::vector<double>& H() const { return h_; }
  const Eigen::VectorXd& g() const { return g_; }
  double MaxDiagonal() const {
    double m = 0.0;
    for (int j = 0; j < g_.size(); ++j)
      m = std::max(m, h_[static_cast<std::size_t>(p_[j + 1] - 1)]);
    return m;
  }

  /// LM damping scale: diag(H) clamped away from zero (Marquardt), or all ones.
  Eigen::VectorXd DampingScale(bool marquardt) const {
    if (!marquardt) return Eigen::VectorXd::Ones(g_.size());
    const double floor = 1e-9 * std::max(MaxDiagonal(), 1e-12);
    Eigen::VectorXd d(g_.size());
    for (Eigen::Index j = 0; j < d.size(); ++j) {
      d[j] = std::max(h_[static_cast<std::size_t>(p_[j + 1] - 1)], floor);
    }
    return d;
  }

  /// Fills H and g at the current poses and returns chi2 there.
  double Linearize(const OptimizerParams& params) {
    std::fill(h_.begin(), h_.end(), 0.0);
    g_.setZero();
    double chi2 = 0.0;
    for (const EdgeSlot& s : layout_.edges) chi2 += LinearizeEdge(s, params);
    for (const CliqueSlot& s : layout_.cliques) chi2 += LinearizeClique(s);
    return chi2;
  }

 private:
  int Block(int node) const { return layout_.block[static_cast<std::size_t>(node)]; }
  const Pose2& Pose(int node) const { return *layout_.poses[static_cast<std::size_t>(node)]; }

  // H_ab += M (rows of block a, columns of block b), a <= b, into the upper triangle.
  void AddBlock(int a, int b, int rank, const Eigen::Matrix3d& M) {
    for (int c = 0; c < 3; ++c) {
      double* col = h_.data() + p_[3 * b + c] + 3 * rank;
      const int rows = (a == b) ? c + 1 : 3;
      for (int r = 0; r < rows; ++r) col[r] += M(r, c);
    }
  }
  void AddOffDiagonal(int a, int b, int rank, const Eigen::Matrix3d& M_ab) {
    if (rank < 0) return;
    if (a < b) {
      AddBlock(a, b, rank, M_ab);
    } else {
      AddBlock(b, a, rank, M_ab.transpose());
    }
  }
  void AddGradient(int a, const Eigen::Vector3d& v) {
    if (a != kNoBlock) g_.segment<3>(3 * a) += v;
  }

  double LinearizeEdge(const EdgeSlot& s, const OptimizerParams& params) {
    const PoseEdge& edge = *s.edge;
    const Pose2& Xi = Pose(s.i);
    const Pose2& Xj = Pose(s.j);
    const Eigen::Vector3d e = RelativeError(Xi, Xj, edge.T_from_to);
    const KernelValue k = ApplyKernel(e.dot(edge.information * e), edge.robust, params);
    Eigen::Matrix3d Ji, Jj;
    RelativeErrorJacobians(Xi, Xj, edge.T_from_to, &Ji, &Jj);
    const Eigen::Matrix3d W = k.weight * edge.information;
    const Eigen::Matrix3d WJi = W * Ji, WJj = W * Jj;
    const int a = Block(s.i), b = Block(s.j);
    if (a != kNoBlock) AddBlock(a, a, s.rank_ii, Ji.transpose() * WJi);
    if (b != kNoBlock) AddBlock(b, b, s.rank_jj, Jj.transpose() * WJj);
    AddOffDiagonal(a, b, s.rank_ij, Ji.transpose() * WJj);
    const Eigen::Vector3d We = W * e;
    AddGradient(a, Ji.transpose() * We);
    AddGradient(b, Jj.transpose() * We);
    return k.cost;
  }

  // Root-relative stacked errors (pose_graph.hpp): block row j depends on root and n_j.
  double LinearizeClique(const CliqueSlot& s) {
    const CliqueFactor& c = *s.clique;
    const std::size_t m = s.nodes.size();
    const Eigen::Index k = static_cast<Eigen::Index>(m - 1);
    Eigen::VectorXd e(3 * k);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3 * k, 3 * (k + 1));
    const Pose2& Xr = Pose(s.nodes[0]);
    for (Eigen::Index j = 0; j < k; ++j) {
      const std::size_t uj = static_cast<std::size_t>(j);
      const Pose2& Xn = Pose(s.nodes[uj + 1]);
      e.segment<3>(3 * j) = RelativeError(Xr, Xn, c.T_root_node[uj]);
      Eigen::Matrix3d Jr, Jn;
      RelativeErrorJacobians(Xr, Xn, c.T_root_node[uj], &Jr, &Jn);
      J.block<3, 3>(3 * j, 0) = Jr;
      J.block<3, 3>(3 * j, 3 * (j + 1)) = Jn;
    }
    const Eigen::MatrixXd WJ = c.information * J;
    const Eigen::MatrixXd H = J.transpose() * WJ;
    const Eigen::VectorXd g = J.transpose() * (c.information * e);
    std::size_t pair = 0;
    for (std::size_t u = 0; u < m; ++u) {
      const int a = Block(s.nodes[u]);
      AddGradient(a, g.segment<3>(3 * static_cast<Eigen::Index>(u)));
      for (std::size_t v = u; v < m; ++v, ++pair) {
        const int b = Block(s.nodes[v]);
        if (a == kNoBlock || b == kNoBlock) continue;
        const Eigen::Matrix3d M =
            H.block<3, 3>(3 * static_cast<Eigen::Index>(u), 3 * static_cast<Eigen::Index>(v));
        if (a == b) {
          // Two clique members share a block only if a node repeats: add both halves.
          AddBlock(a, a, s.ranks[pair], u == v ? M : Eigen::Matrix3d(M + M.transpose()));
        } else {
          AddOffDiagonal(a, b, s.ranks[pair], M);
        }
      }
    }
    return e.dot(c.information * e);
  }

  const Layout& layout_;
  const int* p_;
  std::vector<double> h_;
  Eigen::VectorXd g_;
};

// ---------------------------------------------------------------------------------------
// Objective and updates.
double Chi2(const Layout& layout, const OptimizerParams& params) {
  double chi2 = 0.0;
  for (const EdgeSlot& s : layout.edges) {
    const Eigen::Vector3d e =
        RelativeError(*layout.poses[static_cast<std::size_t>(s.i)],
                      *layout.poses[static_cast<std::size_t>(s.j)], s.edge->T_from_to);
    chi2 += ApplyKernel(e.dot(s.edge->information * e), s.edge->robust, params).cost;
  }
  for (const CliqueSlot& s : layout.cliques) {
    const Eigen::Index k = static_cast<Eigen::Index>(s.nodes.size() - 1);
    Eigen::VectorXd e(3 * k);
    const Pose2& Xr = *layout.poses[static_cast<std::size_t>(s.nodes[0])];
    for (Eigen::Index j = 0; j < k; ++j) {
      const std::size_t uj = static_cast<std::size_t>(j);
      e.segment<3>(3 * j) = RelativeError(
          Xr, *layout.poses[static_cast<std::size_t>(s.nodes[uj + 1])], s.clique->T_root_node[uj]);
    }
    chi2 += e.dot(s.clique->information * e);
  }
  return chi2;
}

void ApplyStep(const Layout& layout, const Eigen::VectorXd& dx) {
  for (std::size_t k = 0; k < layout.poses.size(); ++k) {
    const int a = layout.block[k];
    if (a == kNoBlock) continue;
    Pose2& x = *layout.poses[k];
    x = Pose2(x.x + dx[3 * a], x.y + dx[3 * a + 1], x.theta + dx[3 * a + 2]);
  }
}

std::vector<Pose2> Snapshot(const Layout& layout) {
  std::vector<Pose2> out;
  out.reserve(layout.poses.size());
  for (const Pose2* p : layout.poses) out.push_back(*p);
  return out;
}

void Restore(const Layout& layout, const std::vector<Pose2>& saved) {
  for (std::size_t k = 0; k < saved.size(); ++k) *layout.poses[k] = saved[k];
}

bool Converged(double old_chi2, double new_chi2, const OptimizerParams& params,
               OptimizerSummary* summary) {
  if (new_chi2 < params.absolute_tolerance) {
    summary->message = "chi2 below absolute tolerance";
  } else if (std::abs(old_chi2 - new_chi2) < params.relative_tolerance * old_chi2) {
    summary->message = "relative chi2 decrease below tolerance";
  } else {
    return false;
  }
  summary->converged = true;
  return true;
}

bool StepTiny(const Eigen::VectorXd& dx, const OptimizerParams& params, OptimizerSummary* summary) {
  if (dx.size() > 0 && dx.lpNorm<Eigen::Infinity>() >= params.step_tolerance) return false;
  summary->converged = true;
  summary->message = "step below tolerance";
  return true;
}

// ---------------------------------------------------------------------------------------
// Linear initialization (Carlone et al. 2014, "A fast and accurate approximation for
// planar pose graph optimization", LAGO): the orientation residuals
//   e_theta = wrap(th_j - th_i - th_z)
// are linear in the headings once each wrap is fixed (here: at the current estimate), so
// one weighted linear least-squares solve, with weight the marginal heading information
//   w = Omega_thth - Omega_tht Omega_tt^-1 Omega_ttheta,
// gives all headings; with the headings fixed, e_t = R_z^T (R_i^T (t_j - t_i) - t_z) is
// linear in the positions, and a second solve gives those (weight Omega_tt). Edges only:
// clique factors and robust kernels are ignored here; the result is kept only when it
// lowers the objective (Optimize checks).
using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

// Adds w * (x_b - x_a - c)^T M (x_b - x_a - c) for k-dimensional blocks a, b (kNoBlock: fixed,
// its value folded into c by the caller) to the normal equations H x = rhs.
template <int K>
void AddDifference(int a, int b, const Eigen::Matrix<double, K, K>& M,
                   const Eigen::Matrix<double, K, 1>& c, Triplets* H, Eigen::VectorXd* rhs) {
  for (int r = 0; r < K; ++r) {
    for (int q = 0; q < K; ++q) {
      if (a != kNoBlock) H->emplace_back(K * a + r, K * a + q, M(r, q));
      if (b != kNoBlock) H->emplace_back(K * b + r, K * b + q, M(r, q));
      if (a != kNoBlock && b != kNoBlock) {
        H->emplace_back(K * a + r, K * b + q, -M(r, q));
        H->emplace_back(K * b + r, K * a + q, -M(r, q));
      }
    }
  }
  const Eigen::Matrix<double, K, 1> Mc = M * c;
  if (a != kNoBlock) rhs->template segment<K>(K * a) -= Mc;
  if (b != kNoBlock) rhs->template segment<K>(K * b) += Mc;
}

bool SolveSparse(int n, const Triplets& triplets, const Eigen::VectorXd& rhs, Eigen::VectorXd* x) {
  SparseMatrix H(n, n);
  H.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(H);
  if (ldlt.info() != Eigen::Success) return false;
  *x = ldlt.solve(rhs);
  return ldlt.info() == Eigen::Success && x->allFinite();
}

double MarginalHeadingInformation(const Eigen::Matrix3d& omega) {
  const Eigen::LDLT<Eigen::Matrix2d> tt(omega.topLeftCorner<2, 2>());
  if (tt.info() != Eigen::Success || !(tt.vectorD().minCoeff() > 0.0)) return omega(2, 2);
  const Eigen::Vector2d c = omega.block<2, 1>(0, 2);
  return std::max(omega(2, 2) - c.dot(tt.solve(c)), 0.0);
}

bool InitializeHeadings(const Layout& layout) {
  Triplets H;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(layout.num_blocks), delta;
  for (const EdgeSlot& s : layout.edges) {
    const Pose2& Xi = *layout.poses[static_cast<std::size_t>(s.i)];
    const Pose2& Xj = *layout.poses[static_cast<std::size_t>(s.j)];
    // Unknowns are heading increments d: residual e + d_j - d_i, i.e. c = -e.
    const double e = NormalizeAngle(Xj.theta - Xi.theta - s.edge->T_from_to.theta);
    const Eigen::Matrix<double, 1, 1> w(MarginalHeadingInformation(s.edge->information));
    AddDifference<1>(layout.block[static_cast<std::size_t>(s.i)],
                     layout.block[static_cast<std::size_t>(s.j)], w,
                     Eigen::Matrix<double, 1, 1>(-e), &H, &rhs);
  }
  if (!SolveSparse(layout.num_blocks, H, rhs, &delta)) return false;
  for (std::size_t k = 0; k < layout.poses.size(); ++k) {
    const int a = layout.block[k];
    if (a == kNoBlock) continue;
    Pose2& x = *layout.poses[k];
    x = Pose2(x.x, x.y, x.theta + delta[a]);
  }
  return true;
}

bool InitializePositions(const Layout& layout) {
  Triplets H;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * layout.num_blocks), t;
  for (const EdgeSlot& s : layout.edges) {
    const Pose2& Xi = *layout.poses[static_cast<std::size_t>(s.i)];
    const Pose2& Xj = *layout.poses[static_cast<std::size_t>(s.j)];
    const Pose2& Z = s.edge->T_from_to;
    const Eigen::Matrix2d Ri = Eigen::Rotation2Dd(Xi.theta).toRotationMatrix();
    const Eigen::Matrix2d Riz = Eigen::Rotation2Dd(Xi.theta + Z.theta).toRotationMatrix();
    const Eigen::Matrix2d W = Riz * s.edge->information.topLeftCorner<2, 2>() * Riz.transpose();
    // t_j - t_i = R_i t_z; a fixed end's position moves into the constant.
    Eigen::Vector2d c = Ri * Eigen::Vector2d(Z.x, Z.y);
    const int a = layout.block[static_cast<std::size_t>(s.i)];
    const int b = layout.block[static_cast<std::size_t>(s.j)];
    if (a == kNoBlock) c += Eigen::Vector2d(Xi.x, Xi.y);
    if (b == kNoBlock) c -= Eigen::Vector2d(Xj.x, Xj.y);
    AddDifference<2>(a, b, W, c, &H, &rhs);
  }
  if (!SolveSparse(2 * layout.num_blocks, H, rhs, &t)) return false;
  for (std::size_t k = 0; k < layout.poses.size(); ++k) {
    const int a = layout.block[k];
    if (a == kNoBlock) continue;
    Pose2& x = *layout.poses[k];
    x = Pose2(t[2 * a], t[2 * a + 1], x.theta);
  }
  return true;
}

// ---------------------------------------------------------------------------------------
// Levenberg-Marquardt with Nielsen's damping update.
void RunLevenbergMarquardt(const Layout& layout, Cholmod* solver, System* system,
                           const OptimizerParams& params, double chi2, OptimizerSummary* summary) {
  const bool marquardt = params.scale_damping;
  Eigen::VectorXd D = system->DampingScale(marquardt);
  // lambda_0 = tau (Marquardt) or tau * max diag(H) (Nielsen / g2o; D is all ones there).
  double lambda = params.initial_lambda_factor * (marquardt ? 1.0 : system->MaxDiagonal());
  lambda = std::max(lambda, 1e-300);
  double nu = 2.0;
  Eigen::VectorXd dx;
  summary->message = "maximum iterations reached";
  while (summary->iterations < params.max_iterations) {
    ++summary->iterations;
    if (!solver->Solve(system->H(), lambda, D, -system->g(), &dx)) {
      ++summary->factorization_failures;
      lambda *= nu;
      nu *= 2.0;
      continue;
    }
    if (StepTiny(dx, params, summary)) break;
    const std::vector<Pose2> saved = Snapshot(layout);
    ApplyStep(layout, dx);
    const double new_chi2 = Chi2(layout, params);
    const double predicted = dx.dot(lambda * D.cwiseProduct(dx) - system->g());
    const double rho = (chi2 - new_chi2) / predicted;
    if (std::isfinite(new_chi2) && new_chi2 < chi2 && predicted > 0.0) {
      ++summary->accepted_steps;
      const double old_chi2 = chi2;
      chi2 = new_chi2;
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
      nu = 2.0;
      if (Converged(old_chi2, chi2, params, summary)) break;
      system->Linearize(params);
      D = system->DampingScale(marquardt);
    } else {
      Restore(layout, saved);
      ++summary->rejected_steps;
      lambda *= nu;
      nu *= 2.0;
      if (lambda > 1e40) {
        summary->message = "damping exhausted: no further decrease";
        summary->converged = true;
        break;
      }
    }
  }
  summary->final_chi2 = chi2;
  summary->final_lambda = lambda;
}

// Gauss-Newton: no trial evaluations; chi2 comes with each linearization. A non-SPD system
// gets a small damping that grows until the factorization succeeds.
void RunGaussNewton(const Layout& layout, Cholmod* solver, System* system,
                    const OptimizerParams& params, double chi2, OptimizerSummary* summary) {
  bool stale = false;  // values moved since the last chi2
  const Eigen::VectorXd ones = system->DampingScale(false);
  Eigen::VectorXd dx;
  summary->message = "maximum iterations reached";
  while (summary->iterations < params.max_iterations) {
    ++summary->iterations;
    double lambda = 0.0;
    while (!solver->Solve(system->H(), lambda, ones, -system->g(), &dx)) {
      ++summary->factorization_failures;
      lambda = lambda == 0.0 ? 1e-9 * std::max(system->MaxDiagonal(), 1e-12) : 10.0 * lambda;
      if (lambda > 1e40) break;
    }
    summary->final_lambda = lambda;
    if (lambda > 1e40) {
      summary->message = "factorization failed";
      break;
    }
    if (StepTiny(dx, params, summary)) break;
    ApplyStep(layout, dx);
    ++summary->accepted_steps;
    if (summary->iterations == params.max_iterations) {
      stale = true;  // skip the linearization nobody would use
      break;
    }
    const double new_chi2 = system->Linearize(params);
    if (Converged(chi2, new_chi2, params, summary)) {
      chi2 = new_chi2;
      break;
    }
    chi2 = new_chi2;
  }
  if (stale && params.evaluate_final_chi2) chi2 = Chi2(layout, params);
  summary->final_chi2 = chi2;
}

bool AnyRobustEdge(const Layout& layout, const OptimizerParams& params) {
  if (params.robust_kernel == RobustKernel::kNone) return false;
  return std::any_of(layout.edges.begin(), layout.edges.end(),
                     [](const EdgeSlot& s) { return s.edge->robust; });
}

// Runs the linear initialization and keeps it only if it lowers the objective.
void MaybeInitialize(const Layout& layout, const OptimizerParams& params,
                     OptimizerSummary* summary) {
  const std::vector<Pose2> saved = Snapshot(layout);
  const bool solved = InitializeHeadings(layout) && InitializePositions(layout);
  const double chi2 = solved ? Chi2(layout, params) : std::numeric_limits<double>::infinity();
  summary->initialization_chi2 = chi2;
  summary->initialization_used = std::isfinite(chi2) && chi2 < summary->initial_chi2;
  if (!summary->initialization_used) Restore(layout, saved);
}

NodeId ChooseAnchor(const PoseGraph& graph, const OptimizerParams& params) {
  if (params.anchor) {
    if (!graph.HasNode(*params.anchor)) {
      throw std::invalid_argument("Optimize: anchor node is not in the graph");
    }
    return *params.anchor;
  }
  return graph.NodeIds().front();
}

}  // namespace

OptimizerSummary Optimize(const PoseGraph& graph, Values* values, const OptimizerParams& params) {
  const auto start = std::chrono::steady_clock::now();
  OptimizerSummary summary;
  if (graph.NumNodes() == 0) {
    summary.converged = true;
    summary.message = "empty graph";
    return summary;
  }
  const Layout layout = BuildLayout(graph, values, ChooseAnchor(graph, params));
  Cholmod solver(layout, params.linear_solver);
  System system(layout, solver.ColPtr(), solver.Nnz());
  summary.initial_chi2 = Chi2(layout, params);
  if (params.linear_initialization && layout.num_blocks > 0 && layout.cliques.empty() &&
      !AnyRobustEdge(layout, params)) {
    MaybeInitialize(layout, params, &summary);
  }
  const double start_chi2 = system.Linearize(params);
  summary.final_chi2 = start_chi2;
  if (layout.num_blocks == 0 || start_chi2 < params.absolute_tolerance) {
    summary.converged = true;
    summary.message =
        layout.num_blocks == 0 ? "nothing to optimize" : "chi2 below absolute tolerance";
  } else if (params.method == OptimizerMethod::kGaussNewton) {
    RunGaussNewton(layout, &solver, &system, params, start_chi2, &summary);
  } else {
    RunLevenbergMarquardt(layout, &solver, &system, params, start_chi2, &summary);
  }
  summary.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

bool ParseOptimizerMethod(const std::string& name, OptimizerMethod* method) {
  if (name == "lm") {
    *method = OptimizerMethod::kLevenbergMarquardt;
  } else if (name == "gn") {
    *method = OptimizerMethod::kGaussNewton;
  } else {
    return false;
  }
  return true;
}

double ComputeChi2(const PoseGraph& graph, const Values& values, const OptimizerParams& params) {
  if (graph.NumNodes() == 0) return 0.0;
  Values copy = values;  // the layout holds mutable pointers; the copy keeps `values` const
  const Layout layout = BuildLayout(graph, &copy, graph.NodeIds().front());
  return Chi2(layout, params);
}

}  // namespace lifelong::slam
