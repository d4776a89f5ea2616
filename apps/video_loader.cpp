// LoadVideoModule (apps/video_module.hpp), in the commands module.
#include "apps/module_loader.hpp"
#include "apps/video_module.hpp"

namespace lifelong::apps {

eval::FrameSinkOpener LoadVideoModule() {
  using Entry = const VideoModule* (*)();
  const auto entry = reinterpret_cast<Entry>(ModuleEntry(kVideoModuleFile, kVideoModuleSymbol));
  return entry()->open;
}

}  // namespace lifelong::apps
