// The matcher's coarse levels built only where a search reads them (ReferenceGrid::
// PrepareBounds): every read a search can make is the exact max of the fine table, and a
// match against a grid built that way is the match against a grid built whole. Each grid is
// first built over other points, so a tile left unbuilt holds stale values, not zeros.
#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {
namespace {

std::vector<Eigen::Vector2d> RandomPoints(std::mt19937* rng, int n, double lo, double hi) {
  std::uniform_real_distribution<double> coord(lo, hi);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < n; ++i) points.emplace_back(coord(*rng), coord(*rng));
  return points;
}

// A grid of `points` whose memory held a larger, denser table before.
void BuildOverStaleTables(const std::vector<Eigen::Vector2d>& points, const MatcherConfig& config,
                          std::mt19937* rng, ReferenceGrid* grid) {
  grid->Build(RandomPoints(rng, 3000, -9.0, 9.0), config);
  grid->PrepareAllBounds();
  grid->Build(points, config);
}

// Max of the fine table over [x, x + side)^2, cells outside counting 0.
float BruteBound(const ReferenceGrid& grid, int x, int y, int side) {
  float m = 0.0f;
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) m = std::max(m, grid.Likelihood(x + i, y + j));
  }
  return m;
}

TEST(ReferenceGridLevelsTest, EveryReadWithinReachOfTheQueryCellsIsExact) {
  std::mt19937 rng(5);
  MatcherConfig config;
  config.resolution_m = 0.05;
  config.sigma_m = 0.05;
  config.coarse_factor = 8;
  ReferenceGrid grid;
  BuildOverStaleTables(RandomPoints(&rng, 60, -3.0, 3.0), config, &rng, &grid);
  ASSERT_EQ(grid.num_levels(), 4);
  // Query cells in blocks wider than a tile (so some lie on a tile's last row and column,
  // whose reads reach into the next tile's last row), one block past the table's edge.
  std::vector<std::vector<Eigen::Vector2i>> cells(2);
  for (const Eigen::Vector2i& corner :
       {Eigen::Vector2i(20, 30), Eigen::Vector2i(grid.width() - 2, 5),
        Eigen::Vector2i(-12, grid.height() / 2)}) {
    for (int n = 0; n < 81; ++n)
      cells[static_cast<std::size_t>(n % 2)].push_back(corner + Eigen::Vector2i(n % 9, n / 9));
  }
  const int reach = 8, top = 3;
  grid.PrepareBounds(cells, reach, top);
  for (const auto& rotated : cells) {
    for (const Eigen::Vector2i& c : rotated) {
      for (int j = -reach; j <= reach; ++j) {
        for (int i = -reach; i <= reach; ++i) {
          for (int level = 1; level <= top; ++level) {
            ASSERT_EQ(grid.Bound(level, c.x() + i, c.y() + j),
                      BruteBound(grid, c.x() + i, c.y() + j, 1 << level))
                << "level " << level << " at " << c.x() + i << ", " << c.y() + j;
          }
        }
      }
    }
  }
}

TEST(ReferenceGridLevelsTest, AMatchIsTheSameAsAgainstAGridBuiltWhole) {
  std::mt19937 rng(9);
  MatcherConfig config;  // the matcher's defaults: 3 cm cells, 16-cell blocks
  std::vector<Eigen::Vector2d> reference = RandomPoints(&rng, 400, -6.0, 6.0);
  // A scan of part of the reference, moved by a known offset.
  const Pose2 offset(0.12, -0.07, 0.05);
  std::vector<Eigen::Vector2d> query;
  for (const Eigen::Vector2d& p : reference) {
    if (p.norm() > 4.0) continue;
    double x = 0.0, y = 0.0;
    offset.Inverse().Apply(p.x(), p.y(), &x, &y);
    query.emplace_back(x, y);
  }
  ReferenceGrid whole(reference, config), lazy;
  whole.PrepareAllBounds();
  BuildOverStaleTables(reference, config, &rng, &lazy);
  for (const Pose2& guess : {Pose2(), Pose2(0.2, 0.1, -0.1), Pose2(-0.25, 0.3, 0.2)}) {
    const MatchResult a = Match(whole, query, guess, config);
    const MatchResult b = Match(lazy, query, guess, config);
    EXPECT_EQ(a.T_ref_cur.x, b.T_ref_cur.x);
    EXPECT_EQ(a.T_ref_cur.y, b.T_ref_cur.y);
    EXPECT_EQ(a.T_ref_cur.theta, b.T_ref_cur.theta);
    EXPECT_EQ(a.score, b.score);
    EXPECT_EQ(a.ambiguity, b.ambiguity);
    EXPECT_EQ(a.evaluations, b.evaluations);
    EXPECT_EQ(a.bound_evaluations, b.bound_evaluations);
  }
}

}  // namespace
}  // namespace lifelong::slam
