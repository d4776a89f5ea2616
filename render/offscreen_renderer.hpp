// Headless drawing of a Scene (render/scene.hpp) with legacy fixed-function OpenGL into an
// offscreen target: EGL first (a GPU device, else Mesa's software device or surfaceless
// platform), else OSMesa; no display or X server is needed (issue #7).
//
// The frame: the world view (walls dark grey, laser rays orange with their end points,
// the true robot as a red triangle), then one view per panel (the map as a texture:
// unknown grey 205, free white, occupied black, 255 (1 - p); graph edges by kind in the
// colours of render/palette.hpp; nodes dark blue; the estimate as a red triangle), all at
// one scale, laid out by render/layout.hpp.
//
// Text is not rasterized here: Render returns the titles and counters as TextLabels at
// pixel positions in the title strips, for the caller to draw (eval/figures/video.cpp uses
// cv::putText), so that render depends on no font or image library.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl_context.hpp"
#include "render/layout.hpp"
#include "render/scene.hpp"
#include "types/image.hpp"

namespace lifelong::render {

/// No GL backend could be created, or GL failed while drawing.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A line of text to draw onto the image after rendering.
struct TextLabel {
  std::string text;
  int x_px = 0;         ///< left end, pixels from the left
  int baseline_px = 0;  ///< baseline, pixels from the top
  int height_px = 14;   ///< cap height wanted, pixels
};

/// A rendered frame: the pixels, and the text still to draw onto them.
struct Frame {
  Image image;
  std::vector<TextLabel> labels;
};

struct RendererOptions {
  BackendChoice backend = BackendChoice::kAuto;
  int title_px = 40;            ///< title strip height above each view, pixels
  int margin_px = 4;            ///< gap around each view, pixels
  float wall_width_px = 2.0f;   ///< line width of walls
  float ray_width_px = 1.0f;    ///< line width of laser rays
  float edge_width_px = 1.0f;   ///< line width of graph edges
  float node_size_px = 3.0f;    ///< point size of graph nodes
  float robot_size_px = 14.0f;  ///< robot triangle length, pixels (at least 0.4 m)
};

class OffscreenRenderer {
 public:
  /// A width x height renderer (1..8192 each). Throws RenderError listing why each
  /// backend failed when none works; std::invalid_argument for a bad size.
  static OffscreenRenderer Create(int width, int height, const RendererOptions& options = {});

  OffscreenRenderer(OffscreenRenderer&&) noexcept;
  OffscreenRenderer& operator=(OffscreenRenderer&&) noexcept;
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;
  ~OffscreenRenderer();

  Backend backend() const;
  /// e.g. "egl-device (software)", "osmesa (software)".
  std::string backend_name() const;
  int width() const;
  int height() const;

  /// Draws the scene; the context is current only during the call.
  Frame Render(const Scene& scene);
  /// Draws the scene with views[i] as the content of view i (see ViewBounds), e.g. regions
  /// kept steady over a video. Needs one non-empty entry per view.
  Frame Render(const Scene& scene, const std::vector<Bounds>& views);

 private:
  struct Impl;
  explicit OffscreenRenderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace lifelong::render
