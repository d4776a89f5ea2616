// The entry of liblifelong_video.so (apps/video_module.hpp).
#include "apps/video_module.hpp"

#include "eval/video/video_sink.hpp"

namespace {
const lifelong::apps::VideoModule kModule{&lifelong::eval::OpenVideoSink};
}  // namespace

extern "C" __attribute__((visibility("default"))) const lifelong::apps::VideoModule*
lifelong_video_module_v1() {
  return &kModule;
}
