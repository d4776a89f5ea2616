// Loading the modules that sit beside the `lifelong` program (the build tree and an install
// alike): liblifelong_commands.so (apps/commands.hpp) and liblifelong_video.so
// (apps/video_module.hpp). A module stays loaded for the life of the process.
#pragma once

namespace lifelong::apps {

/// The entry `symbol` of the module `file_name` beside /proc/self/exe, loaded now (all its
/// symbols bound). Throws std::runtime_error naming the module when it cannot be loaded or
/// lacks the symbol.
void* ModuleEntry(const char* file_name, const char* symbol);

}  // namespace lifelong::apps
