// Simulator benchmarks: one 361-beam scan ray-cast in the office world, N simulated seconds
// of corridor_100, and whole runs of corridor_100 / office_1h (sim-seconds per wall-second).
#include <benchmark/benchmark.h>

#include <string>

#include "sim/scenario.hpp"
#include "sim/simulator.hpp"

namespace {

using lifelong::Observation;
using lifelong::sim::LoadScenario;
using lifelong::sim::Scenario;
using lifelong::sim::Simulator;

const std::string kDir = LIFELONG_SOURCE_DIR;

void BM_RayCastOfficeScan361(benchmark::State& state) {
  Scenario s = LoadScenario(kDir + "/scenarios/office_5min.yaml");
  s.laser.beams = 361;
  const Simulator sim(s);
  const lifelong::Pose2 in_corridor(10.0, 9.75, 0.3);
  for (auto _ : state) benchmark::DoNotOptimize(sim.TrueScan(in_corridor));
  state.counters["beams"] =
      benchmark::Counter(361.0 * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RayCastOfficeScan361);

// Simulates the first range(0) seconds of a scenario, scans and odometry included.
void RunFor(benchmark::State& state, const std::string& name, double seconds) {
  const Scenario s = LoadScenario(kDir + "/scenarios/" + name + ".yaml");
  double sim_s = 0.0, collisions = 0.0, scans = 0.0;
  for (auto _ : state) {
    Simulator sim(s);
    Observation obs;
    std::vector<lifelong::Odometry> odom;
    while (sim.time_s() < seconds && sim.Next(&obs, &odom)) scans += 1.0;
    sim_s += sim.time_s();
    collisions += static_cast<double>(sim.collisions().size());
  }
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(sim_s, benchmark::Counter::kIsRate);
  state.counters["sim_s"] = sim_s / static_cast<double>(state.iterations());
  state.counters["scans"] = scans / static_cast<double>(state.iterations());
  state.counters["collisions"] = collisions / static_cast<double>(state.iterations());
}

void BM_Corridor100Seconds(benchmark::State& state) {
  RunFor(state, "corridor_100", static_cast<double>(state.range(0)));
}
BENCHMARK(BM_Corridor100Seconds)->Arg(60)->Unit(benchmark::kMillisecond);

// Whole runs: slow (seconds to a minute); select with --benchmark_filter=Whole.
void BM_WholeCorridor100(benchmark::State& state) { RunFor(state, "corridor_100", 1e9); }
BENCHMARK(BM_WholeCorridor100)->Iterations(1)->Unit(benchmark::kSecond);
void BM_WholeOffice1h(benchmark::State& state) { RunFor(state, "office_1h", 1e9); }
BENCHMARK(BM_WholeOffice1h)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
