#include "render/offscreen_renderer.hpp"

#include <algorithm>
#include <cstring>

#include "render/gl_api.hpp"
#include "render/view_drawer.hpp"

namespace lifelong::render {
namespace {

constexpr Rgb kFrame{235, 235, 235};
constexpr Rgb kWorldBackground{255, 255, 255};
constexpr Rgb kPanelBackground{205, 205, 205};  // as an unknown cell
constexpr Rgb kWall{30, 30, 30};
constexpr Rgb kRay{255, 170, 90};
constexpr Rgb kRayEnd{230, 90, 0};
constexpr Rgb kRobot{210, 0, 0};
constexpr Rgb kNode{20, 40, 160};

std::unique_ptr<GlContext> MakeContext(int width, int height, BackendChoice choice) {
  std::string egl_error, osmesa_error;
  if (choice != BackendChoice::kOsMesaOnly) {
    if (auto gl = CreateEglContext(width, height, &egl_error)) return gl;
  }
  if (choice != BackendChoice::kEglOnly) {
    if (auto gl = CreateOsMesaContext(width, height, &osmesa_error)) return gl;
  }
  std::string why = egl_error;
  if (!osmesa_error.empty()) why += (why.empty() ? "" : "; ") + osmesa_error;
  throw RenderError("no offscreen OpenGL backend could be created (" + why + ")");
}

void AddLabels(const Cell& cell, const std::string& line1, const std::string& line2,
               std::vector<TextLabel>* labels) {
  const int h = std::max(8, cell.title.height * 7 / 20);
  labels->push_back({line1, cell.title.x, cell.title.y + cell.title.height / 2 - 2, h});
  labels->push_back({line2, cell.title.x, cell.title.y + cell.title.height - 4, h});
}

std::string Counters(const Panel& p) {
  return "obs " + std::to_string(p.observation) + "  nodes " + std::to_string(p.node_count) +
         "  edges " + std::to_string(p.edge_count);
}

}  // namespace

struct OffscreenRenderer::Impl {
  std::unique_ptr<GlContext> context;
  GlApi gl;
  RendererOptions options;
  int width = 0, height = 0;
  unsigned texture = 0;

  void DrawWorld(const Scene& scene, const Cell& cell) const;
  void DrawPanel(const Panel& panel, const Cell& cell) const;
  Image ReadBack() const;
};

OffscreenRenderer OffscreenRenderer::Create(int width, int height, const RendererOptions& options) {
  if (width < 1 || height < 1 || width > 8192 || height > 8192)
    throw std::invalid_argument("render: frame size must be 1..8192 pixels, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  auto impl = std::make_unique<Impl>();
  impl->context = MakeContext(width, height, options.backend);
  impl->options = options;
  impl->width = width;
  impl->height = height;
  std::string missing;
  if (!impl->context->MakeCurrent()) throw RenderError("render: cannot make the context current");
  const bool loaded = impl->gl.Load(*impl->context, &missing);
  if (loaded) impl->gl.GenTextures(1, &impl->texture);
  impl->context->Release();
  if (!loaded) throw RenderError(std::string("render: GL entry point missing: ") + missing);
  return OffscreenRenderer(std::move(impl));
}

OffscreenRenderer::OffscreenRenderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
OffscreenRenderer::OffscreenRenderer(OffscreenRenderer&&) noexcept = default;
OffscreenRenderer& OffscreenRenderer::operator=(OffscreenRenderer&&) noexcept = default;
OffscreenRenderer::~OffscreenRenderer() {
  if (impl_ && impl_->texture != 0 && impl_->context->MakeCurrent()) {
    impl_->gl.DeleteTextures(1, &impl_->texture);
    impl_->context->Release();
  }
}

Backend OffscreenRenderer::backend() const { return impl_->context->backend(); }
std::string OffscreenRenderer::backend_name() const {
  const std::string device = impl_->context->device();
  return std::string(BackendName(backend())) + (device.empty() ? "" : " (" + device + ")");
}
int OffscreenRenderer::width() const { return impl_->width; }
int OffscreenRenderer::height() const { return impl_->height; }

void OffscreenRenderer::Impl::DrawWorld(const Scene& scene, const Cell& cell) const {
  ViewDrawer view(gl, height, cell, kWorldBackground);
  view.Lines(scene.rays, kRay, options.ray_width_px);
  std::vector<Pose2> ends;
  for (const Segment& r : scene.rays) ends.emplace_back(r.x1, r.y1, 0.0);
  view.Points(ends, kRayEnd, 2.0f);
  view.Lines(scene.walls, kWall, options.wall_width_px);
  view.Robot(scene.robot_true, std::max(0.4, options.robot_size_px * view.metres_per_pixel()),
             kRobot);
}

void OffscreenRenderer::Impl::DrawPanel(const Panel& panel, const Cell& cell) const {
  ViewDrawer view(gl, height, cell, kPanelBackground);
  view.Map(panel.map, texture);
  for (EdgeKind kind :
       {EdgeKind::kOdometry, EdgeKind::kPrior, EdgeKind::kMarginal, EdgeKind::kLoop}) {
    std::vector<Segment> segments;
    for (const GraphEdge& e : panel.edges)
      if (e.kind == kind) segments.push_back(e.segment);
    view.Lines(segments, EdgeColour(kind), options.edge_width_px);
  }
  view.Points(panel.nodes, kNode, options.node_size_px);
  view.Robot(panel.robot_estimate, std::max(0.4, options.robot_size_px * view.metres_per_pixel()),
             kRobot);
}

Image OffscreenRenderer::Impl::ReadBack() const {
  Image image;
  image.width = width;
  image.height = height;
  std::vector<std::uint8_t> bottom_up(static_cast<std::size_t>(width) * height * 3u);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
  image.rgb.resize(bottom_up.size());
  const std::size_t row = static_cast<std::size_t>(width) * 3u;
  for (int y = 0; y < height; ++y)
    std::memcpy(&image.rgb[static_cast<std::size_t>(y) * row],
                &bottom_up[static_cast<std::size_t>(height - 1 - y) * row], row);
  return image;
}

Frame OffscreenRenderer::Render(const Scene& scene) {
  if (scene.view && !scene.view->Empty())
    return Render(scene, std::vector<Bounds>(1 + scene.panels.size(), *scene.view));
  return Render(scene, ViewBounds(scene));
}

Frame OffscreenRenderer::Render(const Scene& scene, const std::vector<Bounds>& views) {
  if (views.size() != 1 + scene.panels.size())
    throw std::invalid_argument("render: need one view bounds per view");
  Impl& m = *impl_;
  if (!m.context->MakeCurrent()) throw RenderError("render: cannot make the context current");
  m.gl.Disable(GL_SCISSOR_TEST);
  m.gl.Viewport(0, 0, m.width, m.height);
  m.gl.ClearColor(kFrame.r / 255.0f, kFrame.g / 255.0f, kFrame.b / 255.0f, 1.0f);
  m.gl.Clear(GL_COLOR_BUFFER_BIT);
  const LayoutConfig layout{m.width, m.height, m.options.title_px, m.options.margin_px};
  const std::vector<Cell> cells = ComputeLayout(views, layout);
  m.DrawWorld(scene, cells[0]);
  std::vector<TextLabel> labels;
  AddLabels(cells[0], scene.world_title, scene.world_caption, &labels);
  for (std::size_t i = 0; i < scene.panels.size(); ++i) {
    m.DrawPanel(scene.panels[i], cells[i + 1]);
    AddLabels(cells[i + 1], scene.panels[i].title, Counters(scene.panels[i]), &labels);
  }
  m.gl.Disable(GL_SCISSOR_TEST);
  Frame frame{m.ReadBack(), std::move(labels)};
  const GLenum error = m.gl.GetError();
  m.context->Release();
  if (error != GL_NO_ERROR) throw RenderError("render: GL error " + std::to_string(error));
  return frame;
}

}  // namespace lifelong::render
