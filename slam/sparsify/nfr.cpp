// The NFR solver (nfr.hpp steps 3-5): objective, gradient, closed form and the projected
// Newton method. The clique level (topology, Sigma, edges) is in nfr_clique.cpp.
#include "slam/sparsify/nfr.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace lifelong::slam {
namespace {

using Eigen::Index;
using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kArmijo = 1e-4;  ///< sufficient decrease on the projected arc
constexpr int kMaxHalvings = 40;  ///< backtracking steps per direction
constexpr double kActive = 1e-3;  ///< whitened eigenvalues below min(this, KKT) may be held

Index Block(int b) { return static_cast<Index>(3 * b); }

/// J_a M J_b^T for the 3 x d Jacobians a and b (M: d x d).
Matrix3d Sandwich(const MatrixXd& m, const NfrJacobian& a, const NfrJacobian& b) {
  Matrix3d out = Matrix3d::Zero();
  const int ua[2] = {a.from, a.to};
  const int ub[2] = {b.from, b.to};
  const Matrix3d* ja[2] = {&a.J_from, &a.J_to};
  const Matrix3d* jb[2] = {&b.J_from, &b.J_to};
  for (int s = 0; s < 2; ++s) {
    if (ua[s] < 0) continue;
    for (int t = 0; t < 2; ++t) {
      if (ub[t] < 0) continue;
      out += *ja[s] * m.block<3, 3>(Block(ua[s]), Block(ub[t])) * jb[t]->transpose();
    }
  }
  return out;
}

Matrix3d Sym(const Matrix3d& m) { return 0.5 * (m + m.transpose()); }

/// Frobenius-nearest PSD matrix: negative eigenvalues set to 0.
Matrix3d ClipPsd(const Matrix3d& m) {
  const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(Sym(m));
  const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);
  return Sym(eig.eigenvectors() * ev.asDiagonal() * eig.eigenvectors().transpose());
}

/// ln|m| and the factor of m, or false when m is not definite.
bool LogDet(const MatrixXd& m, double* logdet, Eigen::LLT<MatrixXd>* llt) {
  llt->compute(m);
  if (llt->info() != Eigen::Success) return false;
  const VectorXd diag = llt->matrixLLT().diagonal();
  if (!(diag.minCoeff() > 0.0)) return false;
  *logdet = 2.0 * diag.array().log().sum();
  return std::isfinite(*logdet);
}

/// The whitened problem: J~_i = S_i^-1/2 J_i, so J~_i Sigma J~_i^T = S~_i ~ I.
class Whitened {
 public:
  Whitened(const MatrixXd& sigma, const std::vector<NfrJacobian>& jacobians) : d_(sigma.rows()) {
    for (const NfrJacobian& j : jacobians) {
      const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(Sym(Sandwich(sigma, j, j)));
      NfrJacobian w = j;
      w.J_from = eig.operatorInverseSqrt() * j.J_from;
      w.J_to = eig.operatorInverseSqrt() * j.J_to;
      jac_.push_back(w);
      inv_sqrt_.push_back(eig.operatorInverseSqrt());
      sqrt_.push_back(eig.operatorSqrt());
      s_.push_back(Sym(Sandwich(sigma, w, w)));
    }
    Eigen::LLT<MatrixXd> llt;
    if (!LogDet(sigma, &logdet_sigma_, &llt)) {
      throw std::invalid_argument("SolveNfr: Sigma is not positive definite");
    }
  }
  Matrix3d ToWhite(std::size_t i, const Matrix3d& omega) const {
    return Sym(sqrt_[i] * omega * sqrt_[i]);
  }
  Matrix3d FromWhite(std::size_t i, const Matrix3d& x) const {
    return Sym(inv_sqrt_[i] * x * inv_sqrt_[i]);
  }
  /// f = sum tr(X_i S~_i) - ln|Lambda|; +inf when Lambda is not definite. Keeps the factor.
  double Objective(const std::vector<Matrix3d>& x, Eigen::LLT<MatrixXd>* llt) const {
    double trace = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) trace += x[i].cwiseProduct(s_[i]).sum();
    double logdet = 0.0;
    if (!LogDet(NfrInformation(jac_, x, d_), &logdet, llt)) {
      return std::numeric_limits<double>::infinity();
    }
    return trace - logdet;
  }
  double Kl(double f) const {
    const double kl = 0.5 * (f - static_cast<double>(d_) - logdet_sigma_);
    return (kl < 0.0 && kl > -1e-9) ? 0.0 : kl;
  }
  /// Whitened gradient G_i = S~_i - J~_i C J~_i^T, C = Lambda^-1.
  std::vector<Matrix3d> Gradient(const MatrixXd& c) const {
    std::vector<Matrix3d> g;
    for (std::size_t i = 0; i < jac_.size(); ++i) {
      g.push_back(Sym(s_[i] - Sandwich(c, jac_[i], jac_[i])));
    }
    return g;
  }
  /// Hessian of f over the directions `basis[i]` of each X_i (orthonormal, symmetric):
  /// tr(B_ij E_b B_ij^T E_a), B_ij = J~_i C J~_j^T; rows in the order of the bases.
  MatrixXd Hessian(const MatrixXd& c, const std::vector<std::vector<Matrix3d>>& basis) const {
    std::vector<Index> offset{0};
    for (const auto& b : basis) offset.push_back(offset.back() + static_cast<Index>(b.size()));
    MatrixXd h(offset.back(), offset.back());
    for (std::size_t i = 0; i < jac_.size(); ++i) {
      for (std::size_t j = i; j < jac_.size(); ++j) {
        const Matrix3d b = Sandwich(c, jac_[i], jac_[j]);
        for (std::size_t eb = 0; eb < basis[j].size(); ++eb) {
          const Matrix3d m = b * basis[j][eb] * b.transpose();
          for (std::size_t ea = 0; ea < basis[i].size(); ++ea) {
            const double v = basis[i][ea].cwiseProduct(m).sum();
            const Index r = offset[i] + static_cast<Index>(ea);
            const Index q = offset[j] + static_cast<Index>(eb);
            h(r, q) = v;
            h(q, r) = v;
          }
        }
      }
    }
    return h;
  }

 private:
  Index d_;
  std::vector<NfrJacobian> jac_;
  std::vector<Matrix3d> inv_sqrt_, sqrt_, s_;
  double logdet_sigma_ = 0.0;
};

double Inner(const std::vector<Matrix3d>& a, const std::vector<Matrix3d>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i].cwiseProduct(b[i]).sum();
  return s;
}

/// ||P(X - G) - X||_F: zero exactly at a KKT point (X PSD, G PSD, <X, G> = 0).
double KktResidual(const std::vector<Matrix3d>& x, const std::vector<Matrix3d>& g) {
  double s = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) s += (ClipPsd(x[i] - g[i]) - x[i]).squaredNorm();
  return std::sqrt(s);
}

/// Free directions of one X_i for the Newton step (projected Newton with an epsilon-active
/// set, after Bertsekas' two-metric method for bounds, here per eigenvalue): in the
/// eigenbasis Q of X_i, an eigenvalue below epsilon whose gradient pushes it down
/// (q^T G q > 0) is held at 0, i.e. the E_pq with p, q both held are left out; the others,
/// including the rotations E_ab between a held a and a free b, are free.
struct FreeBasis {
  std::vector<Matrix3d> e;      ///< orthonormal symmetric directions
  std::vector<int> held, free;  ///< per direction: (a, b) of a rotation E_ab, else -1
  Eigen::Vector3d lambda;       ///< eigenvalues of X_i
  Matrix3d g_rot;               ///< Q^T G Q
};
std::vector<FreeBasis> FreeBases(const std::vector<Matrix3d>& x, const std::vector<Matrix3d>& g,
                                 double epsilon) {
  std::vector<FreeBasis> bases;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(Sym(x[i]));
    Matrix3d q = eig.eigenvectors();
    FreeBasis fb;
    fb.lambda = eig.eigenvalues();  // ascending
    // The eigenvalues below epsilon span a subspace whose basis X leaves arbitrary (a
    // repeated 0): there take G's eigenvectors, so "G pushes it down" is a property of a
    // direction, not of an arbitrary basis (else a held pair with an indefinite G block
    // would stall the method short of KKT).
    int low = 0;
    while (low < 3 && fb.lambda(low) <= epsilon) ++low;
    if (low > 1) {
      const MatrixXd ql = q.leftCols(low);
      const Eigen::SelfAdjointEigenSolver<MatrixXd> gl(ql.transpose() * g[i] * ql);
      q.leftCols(low) = ql * gl.eigenvectors();
    }
    fb.g_rot = q.transpose() * g[i] * q;
    bool held[3];
    for (int k = 0; k < 3; ++k) held[k] = k < low && fb.g_rot(k, k) > 0.0;
    for (int a = 0; a < 3; ++a) {
      for (int b = a; b < 3; ++b) {
        if (held[a] && held[b]) continue;
        const Matrix3d e = q.col(a) * q.col(b).transpose() + q.col(b) * q.col(a).transpose();
        fb.e.push_back(a == b ? Matrix3d(0.5 * e) : Matrix3d(std::sqrt(0.5) * e));
        const bool rotation = held[a] != held[b];
        fb.held.push_back(rotation ? (held[a] ? a : b) : -1);
        fb.free.push_back(rotation ? (held[a] ? b : a) : -1);
      }
    }
    bases.push_back(fb);
  }
  return bases;
}

/// The curvature the projection adds along rotations: X + t E_ab (a held at 0, b free with
/// eigenvalue l_b) gets an eigenvalue -t^2 / (2 l_b) near q_a, which clipping adds back, so
/// f along the projected arc has the extra second derivative (Q^T G Q)_aa / l_b; between
/// rotations E_ab and E_a'b it is (Q^T G Q)_aa' / l_b (the Riemannian Hessian's correction on
/// matrices of fixed rank). Without it the steps oscillate and converge linearly.
void AddRotationCurvature(const std::vector<FreeBasis>& bases, MatrixXd* h) {
  Index offset = 0;
  for (const FreeBasis& fb : bases) {
    for (std::size_t u = 0; u < fb.e.size(); ++u) {
      for (std::size_t w = 0; w < fb.e.size(); ++w) {
        if (fb.held[u] < 0 || fb.held[w] < 0 || fb.free[u] != fb.free[w]) continue;
        const double l = fb.lambda(fb.free[u]);
        if (!(l > 0.0)) continue;
        (*h)(offset + static_cast<Index>(u), offset + static_cast<Index>(w)) +=
            fb.g_rot(fb.held[u], fb.held[w]) / l;
      }
    }
    offset += static_cast<Index>(fb.e.size());
  }
}

/// Newton direction on the free directions: H d = -g there, 0 on the held ones (a small
/// diagonal shift if H is not definite).
std::vector<Matrix3d> NewtonDirection(const MatrixXd& h, const std::vector<Matrix3d>& g,
                                      const std::vector<FreeBasis>& bases) {
  VectorXd rhs(h.rows());
  Index r = 0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    for (const Matrix3d& e : bases[i].e) rhs(r++) = -e.cwiseProduct(g[i]).sum();
  }
  std::vector<Matrix3d> dir(g.size(), Matrix3d::Zero());
  if (h.rows() == 0) return dir;
  const double scale = std::max(h.diagonal().mean(), std::numeric_limits<double>::min());
  Eigen::LLT<MatrixXd> llt(h);
  for (double shift = 1e-12; llt.info() != Eigen::Success && shift < 1.0; shift *= 100.0) {
    llt.compute(h + shift * scale * MatrixXd::Identity(h.rows(), h.cols()));
  }
  if (llt.info() != Eigen::Success) return dir;
  const VectorXd step = llt.solve(rhs);
  r = 0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    for (const Matrix3d& e : bases[i].e) dir[i] += step(r++) * e;
  }
  return dir;
}

}  // namespace

MatrixXd NfrInformation(const std::vector<NfrJacobian>& jacobians,
                        const std::vector<Matrix3d>& information, Index d) {
  MatrixXd lambda = MatrixXd::Zero(d, d);
  for (std::size_t i = 0; i < jacobians.size(); ++i) {
    const NfrJacobian& j = jacobians[i];
    const int u[2] = {j.from, j.to};
    const Matrix3d* jj[2] = {&j.J_from, &j.J_to};
    for (int s = 0; s < 2; ++s) {
      if (u[s] < 0) continue;
      for (int t = 0; t < 2; ++t) {
        if (u[t] < 0) continue;
        lambda.block<3, 3>(Block(u[s]), Block(u[t])) +=
            jj[s]->transpose() * information[i] * *jj[t];
      }
    }
  }
  return 0.5 * (lambda + lambda.transpose());
}

double NfrKl(const MatrixXd& sigma, const std::vector<NfrJacobian>& jacobians,
             const std::vector<Matrix3d>& information) {
  const Index d = sigma.rows();
  if (d == 0) return 0.0;
  const MatrixXd lambda = NfrInformation(jacobians, information, d);
  Eigen::LLT<MatrixXd> llt;
  double logdet_q = 0.0, logdet_sigma = 0.0;
  if (!LogDet(lambda, &logdet_q, &llt) || !LogDet(sigma, &logdet_sigma, &llt)) {
    return std::numeric_limits<double>::infinity();
  }
  const double kl =
      0.5 * ((lambda.cwiseProduct(sigma)).sum() - static_cast<double>(d) - logdet_q - logdet_sigma);
  return (kl < 0.0 && kl > -1e-9) ? 0.0 : kl;
}

std::vector<Matrix3d> NfrGradient(const MatrixXd& sigma, const std::vector<NfrJacobian>& jacobians,
                                  const std::vector<Matrix3d>& information) {
  const Eigen::LLT<MatrixXd> llt(NfrInformation(jacobians, information, sigma.rows()));
  const MatrixXd c = llt.solve(MatrixXd::Identity(sigma.rows(), sigma.cols()));
  std::vector<Matrix3d> g;
  for (const NfrJacobian& j : jacobians) {
    g.push_back(Sym(Sandwich(sigma, j, j) - Sandwich(c, j, j)));
  }
  return g;
}

std::vector<Matrix3d> NfrTreeInformation(const MatrixXd& sigma,
                                         const std::vector<NfrJacobian>& jacobians) {
  std::vector<Matrix3d> info;
  for (const NfrJacobian& j : jacobians) info.push_back(Sym(Sym(Sandwich(sigma, j, j)).inverse()));
  return info;
}

namespace {

/// Backtracking along the projected arc t -> P(X + t D) (Armijo on the actual change): the
/// first trial that lowers f enough, into *out, *f_out and *llt_out; false when none does.
bool ArcSearch(const Whitened& w, const std::vector<Matrix3d>& x, const std::vector<Matrix3d>& g,
               double f, const std::vector<Matrix3d>& dir, std::vector<Matrix3d>* out,
               double* f_out, Eigen::LLT<MatrixXd>* llt_out) {
  double t = 1.0;
  for (int k = 0; k < kMaxHalvings; ++k, t *= 0.5) {
    std::vector<Matrix3d> trial, change;
    for (std::size_t i = 0; i < x.size(); ++i) {
      trial.push_back(ClipPsd(x[i] + t * dir[i]));
      change.push_back(trial.back() - x[i]);
    }
    const double slope = Inner(g, change);
    if (!(slope < 0.0)) continue;  // not a descent change (projection undid it)
    const double ft = w.Objective(trial, llt_out);
    if (ft <= f + kArmijo * slope) {
      *out = std::move(trial);
      *f_out = ft;
      return true;
    }
  }
  return false;
}

}  // namespace

NfrResult SolveNfr(const MatrixXd& sigma, const std::vector<NfrJacobian>& jacobians,
                   const std::vector<Matrix3d>& start, const NfrOptions& options) {
  if (start.size() != jacobians.size()) {
    throw std::invalid_argument("SolveNfr: one start information per factor");
  }
  const Whitened w(sigma, jacobians);
  std::vector<Matrix3d> x;
  for (std::size_t i = 0; i < start.size(); ++i) x.push_back(ClipPsd(w.ToWhite(i, start[i])));
  Eigen::LLT<MatrixXd> llt;
  double f = w.Objective(x, &llt);
  if (!std::isfinite(f)) throw std::invalid_argument("SolveNfr: Lambda(start) is not definite");
  NfrResult result;
  bool stop = false;
  for (;;) {
    const MatrixXd c = llt.solve(MatrixXd::Identity(sigma.rows(), sigma.cols()));
    const std::vector<Matrix3d> g = w.Gradient(c);
    result.kkt = KktResidual(x, g);
    result.converged = result.kkt <= options.kkt_tolerance;
    if (result.converged || stop || result.iterations >= options.max_iterations) break;
    const auto search = [&](const std::vector<Matrix3d>& dir, std::vector<Matrix3d>* out,
                            double* f_out, Eigen::LLT<MatrixXd>* llt_out) {
      return ArcSearch(w, x, g, f, dir, out, f_out, llt_out);
    };
    std::vector<Matrix3d> next;
    double f_next = f;
    Eigen::LLT<MatrixXd> llt_next;
    std::vector<Matrix3d> minus_g;
    for (const Matrix3d& gi : g) minus_g.push_back(-gi);
    // Bertsekas' epsilon = min(eps0, residual); x2 so that an eigenvalue equal to its own
    // share of the residual (rounding decides) is still held.
    const auto bases = FreeBases(x, g, std::min(kActive, 2.0 * result.kkt));
    std::vector<std::vector<Matrix3d>> directions;
    for (const FreeBasis& fb : bases) directions.push_back(fb.e);
    MatrixXd h = w.Hessian(c, directions);
    AddRotationCurvature(bases, &h);
    bool found = search(NewtonDirection(h, g, bases), &next, &f_next, &llt_next);
    const auto tiny = [&](double f_new) {
      return w.Kl(f) - w.Kl(f_new) <= options.relative_decrease * w.Kl(f);
    };
    if (!found || tiny(f_next)) {  // the projected gradient may do better
      std::vector<Matrix3d> alt;
      double f_alt = f;
      Eigen::LLT<MatrixXd> llt_alt;
      if (search(minus_g, &alt, &f_alt, &llt_alt) && (!found || f_alt < f_next)) {
        next = std::move(alt);
        f_next = f_alt;
        llt_next = std::move(llt_alt);
        found = true;
      }
    }
    if (!found) break;  // no step lowers f at working precision
    stop = tiny(f_next);
    x = std::move(next);
    f = f_next;
    llt = std::move(llt_next);
    ++result.iterations;
  }
  for (std::size_t i = 0; i < x.size(); ++i) result.information.push_back(w.FromWhite(i, x[i]));
  result.kl = w.Kl(f);
  return result;
}

}  // namespace lifelong::slam
