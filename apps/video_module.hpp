// The module liblifelong_video.so: the frame sink of eval/video/video_sink.hpp with what it needs
// (OpenGL through EGL or OSMesa, OpenCV's video writer). `lifelong run --video/--frames`
// loads it; every other run starts without those libraries, which cost ~0.2 s of dynamic
// loading a process (docs/results.md "Exact speed-ups").
#pragma once

#include <memory>

#include "eval/figures/video.hpp"

namespace lifelong::apps {

struct VideoModule {
  std::unique_ptr<eval::FrameSink> (*open)(const eval::VideoOptions&);
};

/// The module's one exported symbol: `extern "C" const VideoModule* <this>()`.
inline constexpr const char* kVideoModuleSymbol = "lifelong_video_module_v1";
inline constexpr const char* kVideoModuleFile = "liblifelong_video.so";

/// Loads the module (apps/module_loader.hpp) and returns its sink opener. Throws
/// std::runtime_error naming the module when it cannot be loaded.
eval::FrameSinkOpener LoadVideoModule();

}  // namespace lifelong::apps
