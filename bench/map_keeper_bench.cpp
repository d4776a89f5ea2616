// The map's share of following the estimate (MapKeeper::Move, which every node a loop closure
// shifts goes through): a long-range scan among others, moved a few centimetres and back.
//   /0 the standard mode: the scan traced at both poses, Remove then Add;
//   /1 the pruned modes, the scan's gain tracked (near the robot): the gain index gives the
//      old cells, GridMap::Move, the other scans' gains kept exact, the scan tracked again;
//   /2 the pruned modes, the scan's gain not tracked (far from the robot) but the others'
//      are: traced at both poses, the tracked gains kept exact.
// The outdoor case of the campus log: most beams reach the grid's 12 m hit range or return
// nothing.
#include <benchmark/benchmark.h>

#include "slam/mapping/map_keeper.hpp"
#include "tests/slam/synthetic_scans.hpp"

namespace lifelong::slam {
namespace {

/// A street 14 m wide between building fronts with gaps, and a few posts: open space on
/// every side, 40 m along.
testing::World StreetWorld() {
  testing::World w;
  for (int i = 0; i < 4; ++i) {
    const double x = -20.0 + 10.0 * i;
    testing::AddRectangle(x, 7.0, x + 7.0, 15.0, &w);
    testing::AddRectangle(x + 3.0, -15.0, x + 9.0, -7.0, &w);
  }
  for (int i = 0; i < 5; ++i) testing::AddRectangle(-16.0 + 8.0 * i, 4.0, -15.8 + 8.0 * i, 4.2, &w);
  return w;
}

void BM_MapKeeperMove(benchmark::State& state) {
  const testing::World street = StreetWorld();
  MapKeeper keeper(GridMapConfig{}, state.range(0) != 0,
                   GainTiming{[] { return nullptr; }, nullptr});
  // Scans every 1.5 m along the street, as the mapper keeps them; the middle one moves.
  NodeStore nodes;
  std::vector<NodeId> others;
  for (NodeId id = 0; id < 9; ++id) {
    NodeData& data = nodes[id];
    data.T_world_map = Pose2(-6.0 + 1.5 * id, 0.3 * (id % 3), 0.05 * id);
    data.scan = testing::SimulateScan(street, data.T_world_map, 361, 3.14159265358979323846, 80.0);
    keeper.Add(id, data.scan, data.T_world_map);
    if (id != 4) others.push_back(id);
  }
  if (state.range(0) == 2) keeper.TrackOnly(others, others, nodes);
  const NodeData& moving = nodes.at(4);
  const Pose2 from = moving.T_world_map, to(from.x + 0.04, from.y - 0.03, from.theta + 0.004);
  for (auto _ : state) {
    keeper.Move(4, moving.scan, from, to, {});
    keeper.Move(4, moving.scan, to, from, {});
  }
  state.counters["cells"] =
      static_cast<double>(keeper.grid().TouchedCells(moving.scan, from).size());
}
BENCHMARK(BM_MapKeeperMove)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace lifelong::slam
