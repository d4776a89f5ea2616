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
//
// Internal to slam: the API is slam/backend/optimizer.hpp (OptimizerParams::linear_initialization).
#pragma once

#include "slam/backend/optimizer_problem.hpp"

namespace lifelong::slam::backend {

/// Re-estimates every free heading by one weighted linear least-squares solve; false (poses
/// untouched) when the system is singular.
bool InitializeHeadings(const Layout& layout);

/// With the headings fixed, re-estimates every free position by a second solve; false (poses
/// untouched) when the system is singular.
bool InitializePositions(const Layout& layout);

}  // namespace lifelong::slam::backend
