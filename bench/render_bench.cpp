// Rendering cost of one 1280x720 frame (issue #7): the corridor world with 181 rays and
// N panels, each with the corridor's walls rasterized at 5 cm as its map and a 250-node
// graph. Arguments: {backend: 0 EGL-first (auto), 1 OSMesa only; panels}.
// Render() = GL drawing + read-back into an RGB image; text labels are not drawn here.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "eval/experiment/simulation.hpp"
#include "eval/metrics/map_quality.hpp"
#include "eval/truth/world_state.hpp"
#include "render/offscreen_renderer.hpp"
#include "sim/scenario.hpp"

namespace {

using namespace lifelong;

render::Scene CorridorScene(int panels) {
  const sim::Scenario scenario =
      sim::LoadScenario(std::string(LIFELONG_SOURCE_DIR) + "/scenarios/corridor_3.yaml");
  const std::vector<Segment> walls = eval::TrueWalls(scenario.world, scenario.duration_s);
  render::Scene scene;
  for (const auto& w : walls) scene.walls.push_back({w.x0, w.y0, w.x1, w.y1});
  const render::Bounds b = render::ViewBounds(scene)[0];
  const double cy = 0.5 * (b.min_y + b.max_y);
  scene.robot_true = Pose2(b.min_x + 5.0, cy, 0.0);
  for (int i = 0; i < 181; ++i) {
    const double a = -M_PI / 2 + i * M_PI / 180;
    scene.rays.push_back(
        {scene.robot_true.x, cy, scene.robot_true.x + 4.0 * std::cos(a), cy + 4.0 * std::sin(a)});
  }
  render::Panel panel;
  panel.map = eval::RasterizeWalls(walls, 0.05);
  for (int i = 0; i < 250; ++i) {
    panel.nodes.emplace_back(b.min_x + 1.0 + i * (b.max_x - b.min_x - 2.0) / 250.0, cy, 0.0);
    if (i > 0) {
      const Pose2& p = panel.nodes[i - 1];
      const Pose2& q = panel.nodes[i];
      panel.edges.push_back({{p.x, p.y, q.x, q.y}, EdgeKind::kOdometry});
    }
  }
  panel.node_count = 250;
  panel.edge_count = 249;
  for (int i = 0; i < panels; ++i) scene.panels.push_back(panel);
  return scene;
}

void BM_Render1280x720(benchmark::State& state) {
  render::RendererOptions options;
  options.backend =
      state.range(0) == 0 ? render::BackendChoice::kAuto : render::BackendChoice::kOsMesaOnly;
  const render::Scene scene = CorridorScene(static_cast<int>(state.range(1)));
  try {
    auto renderer = render::OffscreenRenderer::Create(1280, 720, options);
    state.SetLabel(renderer.backend_name());
    for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(scene));
  } catch (const render::RenderError& e) {
    state.SkipWithError(e.what());
    return;
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["map_cells"] = static_cast<double>(scene.panels[0].map.p_occ.size());
}
BENCHMARK(BM_Render1280x720)
    ->ArgsProduct({{0, 1}, {1, 2, 3}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
