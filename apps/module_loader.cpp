#include "apps/module_loader.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace lifelong::apps {

void* ModuleEntry(const char* file_name, const char* symbol) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const fs::path module = (ec ? fs::path(".") : self.parent_path()) / file_name;
  void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw std::runtime_error(std::string("cannot load ") + dlerror());
  void* entry = dlsym(handle, symbol);
  if (!entry) {
    throw std::runtime_error(module.string() + ": no entry " + symbol + ": " + dlerror());
  }
  return entry;
}

}  // namespace lifelong::apps
