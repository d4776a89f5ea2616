#include "io/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "sensor/input_error.hpp"

namespace lifelong::io {

std::string TempPathFor(const std::string& path) {
  const std::filesystem::path p(path);
  std::filesystem::path tmp = p;
  tmp.replace_filename(p.stem().string() + ".tmp" + p.extension().string());
  return tmp.string();
}

void CommitTempFile(const std::string& tmp_path, const std::string& path) {
  if (std::rename(tmp_path.c_str(), path.c_str()) != 0) {
    std::remove(tmp_path.c_str());
    throw InputError(path, 0, "", "cannot rename the temporary file " + tmp_path + " into place");
  }
}

void WriteThroughTempFile(const std::string& path,
                          const std::function<bool(const std::string& tmp_path)>& write) {
  const std::string tmp = TempPathFor(path);
  bool written = false;
  errno = 0;  // a writer that fails sets it; a stale value must not be reported
  try {
    written = write(tmp);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  if (!written) {
    const int error = errno;  // of the failed open or write, before remove() sets its own
    std::remove(tmp.c_str());
    throw InputError(path, 0, "",
                     std::string("cannot write file") +
                         (error != 0 ? std::string(": ") + std::strerror(error) : ""));
  }
  CommitTempFile(tmp, path);
}

void WriteFileAtomically(const std::string& path, std::string_view bytes) {
  WriteThroughTempFile(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    return static_cast<bool>(out);
  });
}

}  // namespace lifelong::io
