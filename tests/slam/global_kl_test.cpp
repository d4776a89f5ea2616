#include "slam/marginal/global_kl.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "io/graph_file.hpp"
#include "slam/backend/optimizer.hpp"
#include "slam/sparsify/offline_sparsify.hpp"
#include "slam/sparsify/sparsifier.hpp"
#include "tests/slam/marginalization_graphs.hpp"

namespace lifelong::slam {
namespace {

using namespace test_util;  // tests/slam/marginalization_graphs.hpp

PoseGraph Chain(const Values& v, std::mt19937* rng) {
  PoseGraph g;
  for (const auto& [id, pose] : v) g.AddNode(id);
  for (NodeId i = 0; i + 1 < static_cast<NodeId>(v.size()); ++i) {
    g.AddEdge(ConsistentEdge(i, i + 1, v, RandomInfo(rng)));
  }
  g.AddEdge(ConsistentEdge(0, static_cast<NodeId>(v.size()) - 1, v, RandomInfo(rng)));
  return g;
}

TEST(GlobalKl, UnchangedGraphIsZero) {
  std::mt19937 rng(1);
  const Values v = RandomValues({0, 1, 2, 3, 4, 5}, &rng);
  const PoseGraph g = Chain(v, &rng);
  const GlobalKl kl = GlobalKlDivergence(g, v, g, v);
  EXPECT_NEAR(kl.kl, 0.0, 1e-9);
  EXPECT_NEAR(kl.mean_term, 0.0, 1e-20);
  EXPECT_NEAR(kl.rms_offset_m, 0.0, 1e-12);
  EXPECT_EQ(kl.dimension, 15u);
}

TEST(GlobalKl, MeanTermIsTheMahalanobisOffset) {
  // Same graph, kept nodes moved: KL = 1/2 delta^T Lambda delta; a rigid motion of the
  // whole estimate changes nothing (the first kept node is conditioned on).
  std::mt19937 rng(2);
  const Values v = RandomValues({0, 1, 2, 3}, &rng);
  const PoseGraph g = Chain(v, &rng);
  Values moved = v;
  moved[2].x += 0.1;
  const GlobalKl kl = GlobalKlDivergence(g, v, g, moved);
  EXPECT_GT(kl.kl, 1e-4);
  EXPECT_NEAR(kl.kl, kl.mean_term, 1e-9);
  EXPECT_NEAR(kl.rms_offset_m, std::sqrt(0.01 / 4.0), 1e-12);
  Values rigid;
  const Pose2 T(1.0, -2.0, 0.7);
  for (const auto& [id, pose] : v) rigid[id] = T * pose;
  EXPECT_NEAR(GlobalKlDivergence(g, v, g, rigid).kl, 0.0, 1e-9);
}

TEST(GlobalKl, RemovalsWithTwoNodeCliquesLoseNothing) {
  std::mt19937 rng(3);
  const Values v = RandomValues({0, 1, 2, 3, 4, 5}, &rng);
  const PoseGraph g = Chain(v, &rng);
  for (const char* name : {"exact", "glc-dense", "chow-liu"}) {
    PoseGraph sparse = g;
    SparsifyOffline(&sparse, v, {2, 4}, *MakeSparsifier(name));
    const GlobalKl kl = GlobalKlDivergence(g, v, sparse, v);
    // Each removal leaves a two-node clique (a cycle of 6 becomes a cycle of 4), which
    // every method, trees included, represents exactly.
    EXPECT_NEAR(kl.kl, 0.0, 1e-9) << name;
    EXPECT_EQ(kl.dimension, 9u);
  }
}

// The offline protocol on a small real graph (MIT, 808 poses), keeping a quarter.
class RealGraph : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string path = LIFELONG_SHARED_DIR "/datasets/pose_graphs/MIT.g2o";
    if (!std::filesystem::exists(path)) return;
    io::GraphFile file = io::ReadGraphFile(path);
    file_ = new Loaded{PoseGraph::FromFactors(file.factors), std::move(file.values)};
    Optimize(file_->graph, &file_->values);
  }
  static void TearDownTestSuite() { delete file_; }
  static double Kl(const std::string& method) {
    SparsifierConfig config;
    config.means = FactorMeans::kGradient;
    PoseGraph sparse = file_->graph;
    SparsifyOffline(&sparse, file_->values, RemovalForKeepShare(sparse.NodeIds(), 0.25),
                    *MakeSparsifier(method, config));
    Values x;
    for (NodeId id : sparse.NodeIds()) x[id] = file_->values.at(id);
    Optimize(sparse, &x);
    return GlobalKlDivergence(file_->graph, file_->values, sparse, x).kl;
  }
  struct Loaded {
    PoseGraph graph;
    Values values;
  };
  static Loaded* file_;
};
RealGraph::Loaded* RealGraph::file_ = nullptr;

TEST_F(RealGraph, ExactAndGlcDenseLoseNothing) {
  if (!file_) GTEST_SKIP() << "../shared/datasets/pose_graphs/MIT.g2o not found";
  EXPECT_LT(Kl("exact"), 1e-6);
  EXPECT_LT(Kl("glc-dense"), 1e-6);
}

TEST_F(RealGraph, EveryMethodBeatsNaive) {
  if (!file_) GTEST_SKIP() << "../shared/datasets/pose_graphs/MIT.g2o not found";
  const double naive = Kl("naive");
  EXPECT_GT(naive, 1.0);
  for (const char* name : {"exact", "chow-liu", "glc-dense", "glc"}) {
    EXPECT_LT(Kl(name), naive) << name;
  }
  EXPECT_GT(Kl("glc"), 1e-3);  // a tree of a loopy marginal loses something
}

}  // namespace
}  // namespace lifelong::slam
