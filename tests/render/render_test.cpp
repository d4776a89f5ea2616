// Layout arithmetic by hand, and pixels of a tiny known scene with every GL backend that
// can be created here (skipped with a message when none can).
#include <gtest/gtest.h>

#include <string>

#include "render/layout.hpp"
#include "render/offscreen_renderer.hpp"

namespace lifelong::render {
namespace {

TEST(LayoutTest, TwoCellsSideBySideAtTenPixelsPerMetre) {
  // 200x100 frame, no title or margin, a 10 m square world: one row of two 100x100 views
  // (10 px/m) beats one column of two 200x50 views (5 px/m).
  const std::vector<Cell> cells = ComputeLayout(2, {0, 0, 10, 10}, {200, 100, 0, 0});
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[1].view.x, 100);
  EXPECT_EQ(cells[1].view.y, 0);
  EXPECT_EQ(cells[1].view.width, 100);
  EXPECT_EQ(cells[1].view.height, 100);
  EXPECT_DOUBLE_EQ(cells[0].shown.max_x, 10.0);
}

TEST(LayoutTest, WidensTheShortAxisAroundTheCentre) {
  // One 200x100 view of a 10 m square: x is widened to 20 m, centred on x = 5.
  const std::vector<Cell> cells = ComputeLayout(1, {0, 0, 10, 10}, {200, 110, 10, 0});
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells[0].view.y, 10);
  EXPECT_EQ(cells[0].view.height, 100);
  EXPECT_DOUBLE_EQ(cells[0].shown.min_x, -5.0);
  EXPECT_DOUBLE_EQ(cells[0].shown.max_x, 15.0);
  EXPECT_DOUBLE_EQ(cells[0].shown.min_y, 0.0);
}

TEST(LayoutTest, EachViewCentredOnItsOwnContentAtOneScale) {
  // The world spans x 0..10 m, the map x 100..104 m: both are shown 10 m wide (the
  // larger), at 10 px/m, the second centred on x = 102.
  const std::vector<Cell> cells =
      ComputeLayout({{0, 0, 10, 10}, {100, 3, 104, 7}}, {200, 100, 0, 0});
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_DOUBLE_EQ(cells[0].shown.min_x, 0.0);
  EXPECT_DOUBLE_EQ(cells[1].shown.min_x, 97.0);
  EXPECT_DOUBLE_EQ(cells[1].shown.max_x, 107.0);
  EXPECT_DOUBLE_EQ(cells[1].shown.min_y, 0.0);
}

// World view: x 0..100 px, panel: x 100..200 px, both 10 px/m, row 0 at y = 10 m.
Scene TinyScene() {
  Scene scene;
  scene.view = Bounds{0, 0, 10, 10};
  scene.walls.push_back({1.0, 5.0, 9.0, 5.0});  // pixel rows 49-50, columns 10-90
  scene.robot_true = Pose2(2.0, 2.0, 0.0);
  Panel panel;
  panel.title = "standard";
  panel.map.width = panel.map.height = 10;
  panel.map.resolution_m = 1.0;
  panel.map.p_occ.assign(100, 0.0f);             // free
  panel.map.At(2, 7) = 1.0f;                     // occupied: pixels x 120..129, y 20..29
  panel.map.At(6, 1) = OccupancyGrid::kUnknown;  // pixels x 160..169, y 80..89
  panel.robot_estimate = Pose2(8.0, 8.0, 0.0);
  scene.panels.push_back(panel);
  return scene;
}

// No title strips or margins, so that the views tile the 200x100 frame exactly.
RendererOptions TinyOptions(BackendChoice choice) {
  RendererOptions options;
  options.backend = choice;
  options.title_px = 0;
  options.margin_px = 0;
  return options;
}

void ExpectTinySceneDrawn(BackendChoice choice) {
  const RendererOptions options = TinyOptions(choice);
  std::optional<OffscreenRenderer> renderer;
  try {
    renderer.emplace(OffscreenRenderer::Create(200, 100, options));
  } catch (const RenderError& e) {
    GTEST_SKIP() << "no GL backend of this kind here: " << e.what();
  }
  const Frame frame = renderer->Render(TinyScene());
  const Image& image = frame.image;
  ::testing::Test::RecordProperty("backend", renderer->backend_name());
  ASSERT_EQ(image.rgb.size(), 200u * 100u * 3u);
  using Px = std::array<std::uint8_t, 3>;
  EXPECT_LT(image.Pixel(50, 49)[0], 60) << renderer->backend_name() << ": wall row 49";
  EXPECT_LT(image.Pixel(50, 50)[0], 60) << "wall row 50";
  EXPECT_EQ(image.Pixel(50, 30), (Px{255, 255, 255})) << "world background";
  EXPECT_EQ(image.Pixel(95, 50), (Px{255, 255, 255})) << "past the wall's end";
  EXPECT_EQ(image.Pixel(125, 25), (Px{0, 0, 0})) << "occupied cell";
  EXPECT_EQ(image.Pixel(145, 75), (Px{255, 255, 255})) << "free cell";
  EXPECT_EQ(image.Pixel(165, 85), (Px{205, 205, 205})) << "unknown cell";
  const Px robot = image.Pixel(21, 80);  // true robot at (2, 2) m: pixel (20, 80)
  EXPECT_GT(robot[0], 150);
  EXPECT_LT(robot[1], 60);
  const Px estimate = image.Pixel(181, 20);  // estimate at (8, 8) in the panel
  EXPECT_GT(estimate[0], 150);
  EXPECT_LT(estimate[1], 60);
  ASSERT_EQ(frame.labels.size(), 4u);
  EXPECT_EQ(frame.labels[2].text, "standard");
  EXPECT_EQ(frame.labels[3].text, "obs 0  nodes 0  edges 0");
}

TEST(OffscreenRendererTest, TinySceneWithAnyBackend) { ExpectTinySceneDrawn(BackendChoice::kAuto); }
TEST(OffscreenRendererTest, TinySceneWithEgl) { ExpectTinySceneDrawn(BackendChoice::kEglOnly); }
TEST(OffscreenRendererTest, TinySceneWithOsMesa) {
  ExpectTinySceneDrawn(BackendChoice::kOsMesaOnly);
}

TEST(OffscreenRendererTest, EglAndOsMesaInterleavedDrawTheSamePixels) {
  const RendererOptions egl_options = TinyOptions(BackendChoice::kEglOnly);
  const RendererOptions osmesa_options = TinyOptions(BackendChoice::kOsMesaOnly);
  std::optional<OffscreenRenderer> egl, osmesa;
  try {
    egl.emplace(OffscreenRenderer::Create(200, 100, egl_options));
    osmesa.emplace(OffscreenRenderer::Create(200, 100, osmesa_options));
  } catch (const RenderError& e) {
    GTEST_SKIP() << "needs both EGL and OSMesa: " << e.what();
  }
  const Scene scene = TinyScene();
  const Image a = egl->Render(scene).image;
  const Image b = osmesa->Render(scene).image;
  const Image c = egl->Render(scene).image;  // EGL again after OSMesa was current
  EXPECT_EQ(a.rgb, c.rgb);
  EXPECT_EQ(a.Pixel(125, 25), b.Pixel(125, 25));
  EXPECT_EQ(c.Pixel(125, 25), (std::array<std::uint8_t, 3>{0, 0, 0}));
  EXPECT_LT(c.Pixel(50, 50)[0], 60);
}

}  // namespace
}  // namespace lifelong::render
