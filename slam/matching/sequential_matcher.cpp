#include "slam/matching/sequential_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "slam/matching/match_degeneracy.hpp"
#include "slam/matching/scan_refiner.hpp"

namespace lifelong::slam {

Eigen::Matrix3d OdometryInformation(const IncrementalConfig& c, const Pose2& delta) {
  const double sxy = c.odom_sigma_xy_m + c.odom_sigma_xy_per_m * Norm(delta);
  const double sth = c.odom_sigma_rad + c.odom_sigma_rad_per_rad * std::abs(delta.theta);
  return Eigen::Vector3d(1.0 / (sxy * sxy), 1.0 / (sxy * sxy), 1.0 / (sth * sth)).asDiagonal();
}

Eigen::Matrix3d LostStepInformation(const IncrementalConfig& c) {
  const double w2 = c.lost_window_m * c.lost_window_m;
  const double t2 = kLostStepWindowRad * kLostStepWindowRad;
  return Eigen::Vector3d(1.0 / w2, 1.0 / w2, 1.0 / t2).asDiagonal();
}

void SequentialMatcher::Remember(NodeId id, std::size_t scan_index, const LaserScan& scan,
                                 const std::vector<Eigen::Vector2d>& points) {
  local_.push_back(
      {id, scan_index,
       config_.surfaces.JoinsAny() ? ScanSurfaces(scan, config_, config_.surfaces) : points});
  while (local_.size() > static_cast<std::size_t>(std::max(config_.local_map_nodes, 1)))
    local_.pop_front();
}

SequentialMatch SequentialMatcher::Match(const ScanPoseFn& scan_pose, const Pose2& X_last,
                                         const Pose2& delta,
                                         const std::vector<Eigen::Vector2d>& points,
                                         bool odometry_lost) {
  grid_built_ = false;
  SequentialMatch out = MatchStep(scan_pose, X_last, delta, points, odometry_lost);
  grid_anchor_.reset();
  if (grid_built_) grid_anchor_ = out.X_new;
  return out;
}

std::optional<Pose2> SequentialMatcher::RefineBetween(const std::vector<Eigen::Vector2d>& points,
                                                      const Pose2& T_last_scan) const {
  if (!grid_anchor_ || !(config_.between_refine_m > 0.0) || points.size() < 10) {
    return std::nullopt;
  }
  const RefinedPose r = RefinePose(grid_, points, *grid_anchor_ * T_last_scan,
                                   config_.between_refine_m, config_.between_refine_rad);
  if (!(r.score >= config_.matcher.min_score)) return std::nullopt;
  return Between(*grid_anchor_, r.T_ref_cur);
}

SequentialMatch SequentialMatcher::MatchStep(const ScanPoseFn& scan_pose, const Pose2& X_last,
                                             const Pose2& delta,
                                             const std::vector<Eigen::Vector2d>& points,
                                             bool odometry_lost) {
  const Pose2 guess = X_last * delta;
  SequentialMatch out;
  out.X_new = guess;
  out.lost = odometry_lost;
  if (!local_.empty()) out.local_map_from_scan = local_.front().scan_index;
  // The odometry's information is the same in any frame; a lost step has almost none.
  const Eigen::Matrix3d odometry =
      odometry_lost ? LostStepInformation(config_) : OdometryInformation(config_, delta);
  out.information = odometry;
  MatcherConfig mc = config_.matcher;
  if (odometry_lost) {
    mc.linear_window_m = config_.lost_window_m;
    mc.angular_window_rad = kLostStepWindowRad;
  }
  MatchResult match = Search(points, guess, mc, LocalMap(scan_pose));
  const bool refused = match.ok && WeakAndAmbiguous(match, config_);
  if ((!match.ok || refused) && !odometry_lost && config_.recovery_window_m > mc.linear_window_m) {
    MatcherConfig wide = mc;
    wide.linear_window_m = config_.recovery_window_m;
    // The local map again (its scans' surfaces are held): the first search cropped its copy,
    // and keeping one uncropped would cost every step a copy for the rare one that recovers.
    const MatchResult second = Search(points, guess, wide, LocalMap(scan_pose));
    if (Recovers(second, match.score)) {
      match = second;
      out.recovered = true;
    }
  }
  if (!match.ok) return out;
  if (!out.recovered && refused) {
    out.weak = true;
    return out;
  }
  out.X_new = match.T_ref_cur;
  Eigen::Matrix3d information = match.information;  // in the world frame
  if (match.ambiguity > config_.max_ambiguity) {
    TakeDegenerateDirectionFromGuess(guess, odometry, match, &out.X_new, &information);
    out.degenerate = true;
  }
  out.information = RotateIntoFrame(information, out.X_new.theta);
  out.matched = true;
  return out;
}

MatchResult SequentialMatcher::Search(const std::vector<Eigen::Vector2d>& points,
                                      const Pose2& guess, const MatcherConfig& mc,
                                      std::vector<Eigen::Vector2d> reference) {
  CropToSearch(points, guess, mc, &reference);
  if (reference.size() < 10 || points.size() < 10) return {};
  grid_.Build(reference, mc);
  grid_built_ = true;
  return ::lifelong::slam::Match(grid_, points, guess, mc);
}

bool SequentialMatcher::Recovers(const MatchResult& match, double guess_score) const {
  if (!match.ok || match.score < config_.weak_score) return false;
  if (match.ambiguity <= config_.weak_max_ambiguity) return true;
  // Ambiguous: refused only for an odometry guess that scored at least as well as the rival.
  return config_.recover_past_odometry && guess_score < match.ambiguity * match.score;
}

std::vector<Eigen::Vector2d> SequentialMatcher::LocalMap(const ScanPoseFn& scan_pose) const {
  std::vector<Eigen::Vector2d> reference;
  for (const LocalScan& local : local_) {
    const auto world = ToWorld(local.reference, scan_pose(local.id, local.scan_index));
    reference.insert(reference.end(), world.begin(), world.end());
  }
  return reference;
}

}  // namespace lifelong::slam
