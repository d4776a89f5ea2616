// Map figures in a chosen frame and scale (eval/figures/map_figure.hpp, eval/figures/run_maps.hpp):
// the estimate is moved into the truth frame, every figure of a run shares one scale (and, with
// ground truth, one canvas), the true path lies under the graph, and the graph figure has no grid.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "eval/figures/map_figure.hpp"
#include "eval/figures/run_maps.hpp"
#include "eval/metrics/map_quality.hpp"
#include "render/palette.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

cv::Vec3b Pixel(const Image& im, int col, int row) {
  const std::size_t i = (static_cast<std::size_t>(row) * im.width + col) * 3;
  return {im.rgb[i + 2], im.rgb[i + 1], im.rgb[i]};  // BGR, as OpenCV colours are written
}

// 20 x 10 cells of 0.1 m, all free, cell (15, 2) occupied: at x = 1.55, y = 0.25 m.
OccupancyGrid Grid() {
  OccupancyGrid g;
  g.width = 20, g.height = 10, g.resolution_m = 0.1;
  g.p_occ.assign(200, 0.0f);
  g.At(15, 2) = 1.0f;
  return g;
}

TEST(CanvasTest, CoversABoxInWholePixels) {
  const Canvas c = CanvasCovering(-1.0, 2.0, 3.0, 4.0, 0.05);
  EXPECT_EQ(c.width_px, 80);
  EXPECT_EQ(c.height_px, 40);
  const Canvas g = CanvasOfGrid(Grid(), 0.025);
  EXPECT_EQ(g.width_px, 80);
  EXPECT_EQ(g.height_px, 40);
}

// A grid whose frame is rotated by 90 degrees and shifted in the figure frame: the occupied
// cell is drawn where T_frame_grid puts it. (1.55, 0.25) -> (-0.25 + 5, 1.55 + 1).
TEST(RenderFigureTest, ResamplesTheGridIntoTheFigureFrame) {
  const OccupancyGrid grid = Grid();
  FigureLayers layers;
  layers.grid = &grid;
  layers.T_frame_grid = Pose2(5.0, 1.0, M_PI / 2);
  layers.scale_bar = false;
  const Canvas c = CanvasCovering(3.0, 0.0, 6.0, 4.0, 0.05);  // 60 x 80 px
  const Image im = RenderFigure(c, layers);
  ASSERT_EQ(im.width, 60);
  ASSERT_EQ(im.height, 80);
  // The cell covers x in (4.7, 4.8], y in [2.5, 2.6): columns 34-35, image rows 28-29.
  EXPECT_EQ(Pixel(im, 35, 28), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(Pixel(im, 34, 29), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(Pixel(im, 36, 28), cv::Vec3b(255, 255, 255));
  EXPECT_EQ(Pixel(im, 30, 28), cv::Vec3b(255, 255, 255));  // free
  EXPECT_EQ(Pixel(im, 2, 2), cv::Vec3b(205, 205, 205));    // outside the grid: unknown
  // The same pixels from the canvas of the grid's known cells (no margin).
  const Canvas known = CanvasOfKnownCells(grid, layers.T_frame_grid, 0.0, 0.05);
  EXPECT_NEAR(known.x0_m, 4.0, 1e-9);
  EXPECT_NEAR(known.y0_m, 1.0, 1e-9);
  EXPECT_EQ(known.width_px, 20);
  EXPECT_EQ(known.height_px, 40);
}

// Seed Fig. 6.6 hides nothing: the true path is drawn first, thin, and the graph over it.
TEST(RenderFigureTest, TruePathLiesUnderTheGraph) {
  FigureLayers layers;
  layers.scale_bar = false;
  // Lines through pixel centres: y = 1.05 m is image row 9, x = 1.05 m column 10.
  layers.trajectories.push_back({TrajectoryKind::kTrue, {{0.0, 1.05, 0}, {2.0, 1.05, 0}}});
  layers.graph.edges.push_back({0.0, 1.05, 2.0, 1.05, EdgeKind::kMarginal});
  layers.graph.edges.push_back({1.05, 0.0, 1.05, 2.0, EdgeKind::kLoop});
  const Canvas c = CanvasCovering(0.0, 0.0, 2.0, 2.0, 0.1);
  const auto expect_near = [](const cv::Vec3b& p, const render::Rgb& want) {
    EXPECT_NEAR(p[0], want.b, 25);  // anti-aliased: within a tenth of full scale
    EXPECT_NEAR(p[1], want.g, 25);
    EXPECT_NEAR(p[2], want.r, 25);
  };
  const Image im = RenderFigure(c, layers);
  expect_near(Pixel(im, 5, 9), render::EdgeColour(EdgeKind::kMarginal));
  expect_near(Pixel(im, 10, 5), render::EdgeColour(EdgeKind::kLoop));
  EXPECT_EQ(Pixel(im, 3, 3), cv::Vec3b(255, 255, 255));  // no grid: white
  layers.graph = {};
  expect_near(Pixel(RenderFigure(c, layers), 5, 9), render::kTrueTrajectory);
}

TEST(RenderFigureTest, TransformedMovesNodesAndEdges) {
  GraphOverlay g;
  g.nodes = {{1.0, 0.0, 0.0}};
  g.edges = {{{1.0, 0.0, 2.0, 0.0}, EdgeKind::kOdometry}};
  const GraphOverlay t = Transformed(Pose2(0.0, 1.0, M_PI / 2), g);
  EXPECT_NEAR(t.nodes[0].x, 0.0, 1e-12);
  EXPECT_NEAR(t.nodes[0].y, 2.0, 1e-12);
  EXPECT_NEAR(t.nodes[0].theta, M_PI / 2, 1e-12);
  EXPECT_NEAR(t.edges[0].segment.x1, 0.0, 1e-12);
  EXPECT_NEAR(t.edges[0].segment.y1, 3.0, 1e-12);
  EXPECT_EQ(t.edges[0].kind, EdgeKind::kOdometry);
}

/// True when the pixel is within 40 per channel of the colour.
bool Near(const cv::Vec3b& bgr, const render::Rgb& c) {
  return std::abs(bgr[0] - c.b) < 40 && std::abs(bgr[1] - c.g) < 40 && std::abs(bgr[2] - c.r) < 40;
}

// A loop closure joins nodes close together on the path, where the nodes and the odometry
// edges would hide it: it is drawn last, over them, and thicker.
TEST(RenderFigureTest, LoopClosuresAreDrawnOverNodesAndOtherEdges) {
  FigureLayers layers;
  layers.scale_bar = false;
  layers.graph.nodes = {Pose2(1.0, 1.0, 0.0)};
  layers.graph.edges = {{{0.5, 1.0, 1.5, 1.0}, EdgeKind::kLoop},  // listed first
                        {{0.5, 1.0, 1.5, 1.0}, EdgeKind::kOdometry}};
  const Canvas c = CanvasCovering(0.0, 0.0, 2.0, 2.0, 0.05);  // 40 x 40 px, y = 1 m at row 20
  const Image im = RenderFigure(c, layers);
  const render::Rgb loop = render::EdgeColour(EdgeKind::kLoop);
  EXPECT_TRUE(Near(Pixel(im, 20, 19), loop) || Near(Pixel(im, 20, 20), loop));  // on the node
  EXPECT_TRUE(Near(Pixel(im, 14, 19), loop) || Near(Pixel(im, 14, 20), loop));  // on odometry
  int rows = 0;  // the line is two pixels thick
  for (int r = 15; r < 25; ++r) rows += Near(Pixel(im, 14, r), loop);
  EXPECT_GE(rows, 2);
}

std::vector<Observation> Stream(double length_m) {
  std::vector<Observation> s;
  for (int i = 0; i <= 10; ++i) {
    Observation o;
    o.stamp_s = i;
    o.T_odom_robot = Pose2(0.1 * i * length_m, 1.0, 0.0);
    o.T_world_robot_true = Pose2(1.0 + 0.1 * i * length_m, 2.0, 0.0);
    s.push_back(o);
  }
  return s;
}

// With ground truth the canvas is what the laser saw from the true path, plus 1 m, cut
// to the truth map: a route through part of a world is not drawn in a corner of it.
TEST(RunMapFrameTest, TruthFrameIsWhatTheLaserSawAtOneScale) {
  const std::vector<Segment> walls = {{0, 0, 20, 0}, {20, 0, 20, 3}};  // map: [-1, 21] x [-1, 4]
  // No beams: the laser's positions, x in [1, 11] at y = 2, plus 1 m: 12 m -> k = 4.
  const RunMapFrame f = MakeRunMapFrame(Stream(10.0), &walls, 0.05);
  EXPECT_TRUE(f.truth_frame);
  EXPECT_DOUBLE_EQ(f.m_per_px, 0.05 / 4);
  EXPECT_DOUBLE_EQ(f.canvas.x0_m, 0.0);
  EXPECT_DOUBLE_EQ(f.canvas.y0_m, 1.0);
  EXPECT_EQ(f.canvas.width_px, 960);
  EXPECT_EQ(f.canvas.height_px, 160);
  // A "no return" beam ahead reaches x = 41 and one to the left y = 3.5: cut to the map
  // (whole cells: [-1, 21.05] x [-1, 4.05]), [0, 21.05] x [1, 4.05], 21 m -> k = 3.
  std::vector<Observation> seen = Stream(10.0);
  for (Observation& o : seen) {
    o.scan.range_max_m = 30.0;
    o.scan.angle_increment_rad = M_PI / 2;
    o.scan.ranges_m = {30.0f, 1.5f};
  }
  const RunMapFrame g = MakeRunMapFrame(seen, &walls, 0.05);
  EXPECT_DOUBLE_EQ(g.m_per_px, 0.05 / 3);
  const OccupancyGrid truth = RasterizeWalls(walls, 0.05);
  EXPECT_NEAR(truth.origin_x_m + truth.width * 0.05, 21.05, 1e-9);
  EXPECT_EQ(g.canvas.width_px, 1263);
  EXPECT_EQ(g.canvas.height_px, 183);
  EXPECT_EQ(f.true_path.size(), 11u);
  // Without truth the scale follows the odometry path (10 m + 10 m -> 400 cells -> k = 4).
  const RunMapFrame r = MakeRunMapFrame(Stream(10.0), nullptr, 0.05);
  EXPECT_FALSE(r.truth_frame);
  EXPECT_DOUBLE_EQ(r.m_per_px, 0.05 / 4);
  EXPECT_TRUE(r.true_path.empty());
  EXPECT_DOUBLE_EQ(MakeRunMapFrame(Stream(100.0), nullptr, 0.05).m_per_px, 0.05);
}

fs::path TempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("lifelong_eval_" + name);
  fs::remove_all(d);
  fs::create_directories(d / "a");
  fs::create_directories(d / "b");
  fs::create_directories(d / "truth");
  return d;
}

// Every map of a run with ground truth has the truth map's size; a replay's maps share the
// scale, so a mode whose map is twice as large is drawn twice as large.
TEST(RunMapFrameTest, ModeFiguresShareTheTruthCanvasOrTheScale) {
  const fs::path dir = TempDir("run_maps");
  const std::vector<Segment> walls = {{0, 0, 4, 0}, {4, 0, 4, 3}};
  const RunMapFrame f = MakeRunMapFrame(Stream(2.0), &walls, 0.1);
  WriteTruthFiles((dir / "truth").string(), Stream(2.0), RasterizeWalls(walls, 0.1), f);
  EXPECT_TRUE(fs::exists(dir / "truth" / "map.pgm"));
  EXPECT_TRUE(fs::exists(dir / "truth" / "trajectory.tum"));
  WriteModeFigures(dir.string(), "a", Grid(), {}, Pose2(0.5, 0.5, 0.3), f);
  const cv::Mat truth = cv::imread((dir / "truth" / "map.png").string());
  const cv::Mat a = cv::imread((dir / "a" / "map.png").string());
  const cv::Mat graph = cv::imread((dir / "graph_a.png").string());
  ASSERT_FALSE(truth.empty());
  EXPECT_EQ(a.size(), truth.size());
  EXPECT_EQ(graph.size(), truth.size());
  EXPECT_EQ(graph.at<cv::Vec3b>(graph.rows / 2, graph.cols / 2), cv::Vec3b(255, 255, 255));

  const RunMapFrame r = MakeRunMapFrame(Stream(2.0), nullptr, 0.1);
  OccupancyGrid big = Grid();
  big.resolution_m = 0.2;  // the same cells cover twice the metres
  WriteModeFigures(dir.string(), "a", Grid(), {}, std::nullopt, r);
  WriteModeFigures(dir.string(), "b", big, {}, std::nullopt, r);
  const cv::Mat ma = cv::imread((dir / "a" / "map.png").string());
  const cv::Mat mb = cv::imread((dir / "b" / "map.png").string());
  const double margin_px = 2.0 * 1.0 / r.m_per_px;
  EXPECT_NEAR(mb.cols - margin_px, 2.0 * (ma.cols - margin_px), 1.0);
  EXPECT_NEAR(mb.rows - margin_px, 2.0 * (ma.rows - margin_px), 1.0);
}

}  // namespace
}  // namespace lifelong::eval
