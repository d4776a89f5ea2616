#include "slam/matching/scan_refiner.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {
namespace {

constexpr int kMaxIterations = 20;
constexpr int kMaxRetries = 6;  ///< damping up to 1e2 of the largest curvature

/// Mean v of the points at `pose` (the score S / n); with the normal equations when asked.
double Evaluate(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points,
                const Eigen::Vector3d& pose, Eigen::Matrix3d* JtJ, Eigen::Vector3d* Jtr) {
  const double c = std::cos(pose.z()), s = std::sin(pose.z());
  double score = 0.0;
  if (JtJ != nullptr) {
    JtJ->setZero();
    Jtr->setZero();
  }
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2d q(c * p.x() - s * p.y() + pose.x(), s * p.x() + c * p.y() + pose.y());
    Eigen::Vector2d grad;
    const double v = ref.Interpolate(q, JtJ != nullptr ? &grad : nullptr);
    score += v;
    if (JtJ == nullptr) continue;
    const Eigen::Vector2d dq_dtheta(-s * p.x() - c * p.y(), c * p.x() - s * p.y());
    const Eigen::Vector3d J(-grad.x(), -grad.y(), -grad.dot(dq_dtheta));  // d(1 - v)
    *JtJ += J * J.transpose();
    *Jtr += J;  // minus the gradient of sum v
  }
  return points.empty() ? 0.0 : score / static_cast<double>(points.size());
}

}  // namespace

RefinedPose RefinePose(const ReferenceGrid& ref, const std::vector<Eigen::Vector2d>& points_in_cur,
                       const Pose2& start, double max_shift_m, double max_turn_rad) {
  const Eigen::Vector3d x0(start.x, start.y, start.theta);
  const Eigen::Vector3d box(max_shift_m, max_shift_m, max_turn_rad);
  Eigen::Vector3d x = x0;
  RefinedPose out;
  Eigen::Matrix3d JtJ;
  Eigen::Vector3d Jtr;
  double score = Evaluate(ref, points_in_cur, x, &JtJ, &Jtr);
  out.start_score = score;
  // Levenberg-Marquardt: a step that does not raise the score is retried with more damping
  // (the field is only C1 and S is not concave, so a full step can overshoot).
  double damping = 1e-4;
  for (int it = 0; it < kMaxIterations; ++it) {
    const double scale = JtJ.diagonal().maxCoeff();
    if (!(scale > 0.0)) break;
    bool improved = false;
    for (int retry = 0; retry < kMaxRetries && !improved; ++retry, damping *= 10.0) {
      const Eigen::Matrix3d A = JtJ + damping * scale * Eigen::Matrix3d::Identity();
      const Eigen::Vector3d step = A.ldlt().solve(-Jtr);
      if (!step.allFinite()) break;
      const Eigen::Vector3d next = x0 + (x + step - x0).cwiseMax(-box).cwiseMin(box);
      Eigen::Matrix3d next_JtJ;
      Eigen::Vector3d next_Jtr;
      const double next_score = Evaluate(ref, points_in_cur, next, &next_JtJ, &next_Jtr);
      if (!(next_score > score)) continue;
      improved = true;
      const bool converged =
          (next - x).head<2>().norm() < 1e-4 && std::abs(next.z() - x.z()) < 1e-5;
      x = next;
      score = next_score;
      JtJ = next_JtJ;
      Jtr = next_Jtr;
      out.iterations = it + 1;
      damping = std::max(damping / 100.0, 1e-6);  // undo this try's growth, then relax
      if (converged) it = kMaxIterations;
    }
    if (!improved) break;
  }
  out.T_ref_cur = Pose2(x.x(), x.y(), x.z());
  out.score = score;
  return out;
}

}  // namespace lifelong::slam
