// One marginalization (MarginalizeExact/ChowLiu/Naive, no graph edit) of a node with m neighbours,
// with the exact Schur clique, the Chow-Liu tree and the naive composition, m = 3, 6, 10, 20.
// Scene: node 0 at the centre of a ring of m neighbours (random headings, fixed seed),
// each joined to 0 by a random-information edge, consecutive neighbours by odometry.
#include <cmath>
#include <random>

#include <benchmark/benchmark.h>

#include "slam/marginal/marginalization.hpp"

namespace lifelong::slam {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Scene {
  PoseGraph graph;
  Values values;
};

Eigen::Matrix3d RandomInfo(std::mt19937* rng) {
  std::normal_distribution<double> n01(0.0, 1.0);
  Eigen::Matrix3d a;
  for (int i = 0; i < 9; ++i) a(i / 3, i % 3) = n01(*rng);
  return a * a.transpose() + Eigen::Matrix3d::Identity();
}

void Connect(Scene* s, NodeId a, NodeId b, std::mt19937* rng) {
  PoseEdge e;
  e.from = a;
  e.to = b;
  e.T_from_to = Between(s->values.at(a), s->values.at(b));
  e.information = RandomInfo(rng);
  s->graph.AddEdge(e);
}

Scene Ring(int m) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> heading(-3.0, 3.0);
  Scene s;
  s.values[0] = Pose2(0.0, 0.0, 0.3);
  s.graph.AddNode(0);
  for (NodeId i = 1; i <= m; ++i) {
    const double a = 2.0 * kPi * static_cast<double>(i) / m;
    s.values[i] = Pose2(2.0 * std::cos(a), 2.0 * std::sin(a), heading(rng));
    s.graph.AddNode(i);
    Connect(&s, 0, i, &rng);
    if (i > 1) Connect(&s, i - 1, i, &rng);
  }
  return s;
}

using MarginalizeFn = MarginalizationResult (*)(const PoseGraph&, const Values&, NodeId);

void Run(benchmark::State& state, MarginalizeFn marginalize) {
  const Scene s = Ring(static_cast<int>(state.range(0)));
  MarginalizationResult r;
  for (auto _ : state) {
    r = marginalize(s.graph, s.values, 0);
    benchmark::DoNotOptimize(r);
  }
  state.counters["clique_size"] = static_cast<double>(r.clique_size);
  state.counters["pairs"] = static_cast<double>(r.num_pairs);
  state.counters["kl"] = r.kl_divergence;
}

void BM_MarginalizeExact(benchmark::State& state) { Run(state, MarginalizeExact); }
void BM_MarginalizeChowLiu(benchmark::State& state) {
  Run(state,
      [](const PoseGraph& g, const Values& v, NodeId k) { return MarginalizeChowLiu(g, v, k); });
}
void BM_MarginalizeNaive(benchmark::State& state) { Run(state, MarginalizeNaive); }

BENCHMARK(BM_MarginalizeExact)->Arg(3)->Arg(6)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MarginalizeChowLiu)->Arg(3)->Arg(6)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MarginalizeNaive)->Arg(3)->Arg(6)->Arg(10)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace lifelong::slam
