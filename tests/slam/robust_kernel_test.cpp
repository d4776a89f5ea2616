// Robust kernels on loop edges (slam/backend/optimizer.hpp): Huber, Cauchy and dynamic covariance
// scaling against a wrong loop closure.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "slam/backend/optimizer.hpp"
#include "slam/backend/optimizer_problem.hpp"
#include "slam/graph/se2.hpp"
#include "test_graphs.hpp"

namespace lifelong::slam {
namespace {

using test::Edge;
using test::kPi;
using test::Nodes;

// A hexagon with exact odometry and one exact loop, plus one loop that is off_m off.
// robust_ring: the exact loop is robust too (else only the wrong one is).
double WorstErrorWithKernel(RobustKernel kernel, double off_m = 4.0, bool robust_ring = true) {
  Values truth;
  for (int i = 0; i < 6; ++i) {
    const double a = i * kPi / 3.0;
    truth[i] = Pose2(2.0 * std::cos(a), 2.0 * std::sin(a), a + kPi / 2.0);
  }
  PoseGraph g = Nodes(6);
  for (int i = 0; i < 6; ++i) {
    PoseEdge e = Edge(i, (i + 1) % 6, Between(truth[i], truth[(i + 1) % 6]),
                      Eigen::Vector3d(100.0, 100.0, 400.0).asDiagonal());
    e.robust = robust_ring && i == 5;
    g.AddEdge(e);
  }
  PoseEdge wrong = Edge(0, 3, Between(truth[0], truth[3]) * Pose2(off_m, 0.0, 0.0),
                        Eigen::Vector3d(100.0, 100.0, 400.0).asDiagonal());
  wrong.kind = EdgeKind::kLoop;
  wrong.robust = true;
  g.AddEdge(wrong);
  Values v = truth;
  OptimizerParams params;
  params.robust_kernel = kernel;
  params.robust_delta = 1.0;
  Optimize(g, &v, params);
  double worst = 0.0;
  for (int i = 0; i < 6; ++i)
    worst = std::max(worst, std::hypot(v[i].x - truth[i].x, v[i].y - truth[i].y));
  return worst;
}

TEST(Optimizer, RobustKernelDownWeightsGrosslyWrongLoop) {
  const double plain = WorstErrorWithKernel(RobustKernel::kNone);
  const double huber = WorstErrorWithKernel(RobustKernel::kHuber);
  const double cauchy = WorstErrorWithKernel(RobustKernel::kCauchy);
  EXPECT_GT(plain, 0.5);  // least squares splits the 4 m between the two paths
  EXPECT_LT(huber, 0.5 * plain);
  EXPECT_LT(cauchy, 0.05);
}

// A loop 0.5 m off against exact odometry: inside Cauchy's reach, it still pulls; DCS
// switches it off.
TEST(Optimizer, DcsSwitchesOffAModeratelyWrongLoopThatCauchyOnlyDownWeights) {
  const double plain = WorstErrorWithKernel(RobustKernel::kNone, 0.5, false);
  const double cauchy = WorstErrorWithKernel(RobustKernel::kCauchy, 0.5, false);
  const double dcs = WorstErrorWithKernel(RobustKernel::kDcs, 0.5, false);
  // Measured: plain 0.36 m, Cauchy 0.068 m, DCS 0.0098 m (weights 1/(1+s) vs 4/(1+s)^2 at
  // s = 25).
  EXPECT_GT(plain, 0.2);
  EXPECT_LT(dcs, 0.2 * cauchy);
  EXPECT_LT(dcs, 0.02);
}

// DCS's cost is continuous at Phi and its weight is its derivative, the paper's scaling
// factor squared (Agarwal et al. 2013, eq. 15).
TEST(Optimizer, DcsKernelWeightIsTheDerivativeOfItsCost) {
  OptimizerParams params;
  params.robust_kernel = RobustKernel::kDcs;
  params.robust_delta = 1.5;
  const double phi = params.robust_delta * params.robust_delta;
  EXPECT_DOUBLE_EQ(backend::ApplyKernel(0.5 * phi, true, params).cost, 0.5 * phi);
  EXPECT_NEAR(backend::ApplyKernel(phi * (1 + 1e-12), true, params).cost, phi, 1e-9);
  for (const double s : {1.1 * phi, 3.0, 10.0, 100.0, 1e4}) {
    const double h = 1e-6 * s;
    const double slope = (backend::ApplyKernel(s + h, true, params).cost -
                          backend::ApplyKernel(s - h, true, params).cost) /
                         (2 * h);
    const double scale = std::min(1.0, 2.0 * phi / (phi + s));
    EXPECT_NEAR(backend::ApplyKernel(s, true, params).weight, scale * scale, 1e-12);
    EXPECT_NEAR(slope, scale * scale, 1e-6);
  }
  EXPECT_EQ(backend::ApplyKernel(1e4, false, params).weight,
            1.0);  // non-robust edges: least squares
}

}  // namespace
}  // namespace lifelong::slam
