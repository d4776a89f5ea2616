#include "io/output_path.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

namespace fs = std::filesystem;

void RequireNonEmpty(const std::string& path, const std::string& flag) {
  if (path.empty()) throw InputError(flag, 0, "", "the path is empty: give a file or directory");
}

}  // namespace

void CheckWritableFile(const std::string& path, const std::string& flag) {
  RequireNonEmpty(path, flag);
  const fs::path p(path);
  if (p.filename().empty()) throw InputError(path, 0, flag, "names a directory, not a file");
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw InputError(path, 0, flag, "is a directory");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  fs::create_directories(dir, ec);
  if (ec) throw InputError(path, 0, flag, "cannot make " + dir.string() + ": " + ec.message());
  const fs::path probe = dir / (".lifelong-write-test-" + std::to_string(::getpid()));
  std::FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) {
    throw InputError(path, 0, flag,
                     "cannot write in " + dir.string() + ": " + std::strerror(errno));
  }
  std::fclose(f);
  fs::remove(probe, ec);
}

void CheckWritableDirectory(const std::string& path, const std::string& flag) {
  RequireNonEmpty(path, flag);
  std::error_code ec;
  fs::path p = fs::absolute(path, ec);
  while (!ec && !fs::exists(p, ec) && p.has_parent_path() && p != p.parent_path()) {
    p = p.parent_path();
  }
  if (ec || !fs::is_directory(p, ec)) {
    throw InputError(path, 0, flag, p.string() + " exists and is not a directory");
  }
  if (::access(p.c_str(), W_OK | X_OK) != 0) {
    throw InputError(path, 0, flag, "cannot write in " + p.string() + ": " + std::strerror(errno));
  }
}

}  // namespace lifelong::io
