// Files for eval's tests: a whole file as text, and a fresh directory under the system's
// temporary one.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace lifelong::eval {

/// The whole file; empty when it cannot be read.
inline std::string ReadFileText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// <temp>/lifelong_eval_<name>, emptied and created.
inline std::filesystem::path FreshTempDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("lifelong_eval_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace lifelong::eval
