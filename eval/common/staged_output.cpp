// All-or-nothing output directories; see staged_output.hpp.
#include "eval/common/staged_output.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "eval/common/interrupt.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

bool IsEarlierOutput(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_empty(dir, ec) && !ec) return true;
  for (const char* name : {kOutputMarker, "summary.json", "report.html"}) {
    if (fs::exists(dir / name, ec)) return true;
  }
  return false;
}

fs::path Parent(const fs::path& dir) {
  const fs::path abs = fs::absolute(dir).lexically_normal();
  // "runs/x/" normalizes to "runs/x/" with an empty filename; drop it.
  return abs.has_filename() ? abs.parent_path() : abs.parent_path().parent_path();
}

fs::path WithoutTrailingSlash(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();
  return p;
}

}  // namespace

void CheckReplaceableOutput(const std::string& dir) {
  const fs::path p = WithoutTrailingSlash(dir);
  std::error_code ec;
  if (dir.empty()) throw InputError("-o", 0, "", "the path is empty: give an output directory");
  if (p.empty() || p == "." || p == ".." || p == p.root_path()) {
    throw InputError(dir, 0, "-o", "give an output directory of its own, not . or .. or /");
  }
  if (fs::exists(p, ec)) {
    if (!fs::is_directory(p, ec)) throw InputError(dir, 0, "-o", "exists and is not a directory");
    if (!IsEarlierOutput(p)) {
      throw InputError(dir, 0, "-o",
                       "exists and is not a lifelong output directory (no summary.json or " +
                           std::string(kOutputMarker) + "); it would be replaced: choose another");
    }
  }
  const fs::path parent = Parent(p);
  fs::create_directories(parent, ec);
  if (ec || access(parent.c_str(), W_OK | X_OK) != 0) {
    throw InputError(dir, 0, "-o", "cannot write in " + parent.string());
  }
}

StagedOutput::StagedOutput(std::string final_dir)
    : final_(WithoutTrailingSlash(final_dir).string()) {
  CheckReplaceableOutput(final_);
  staging_ = final_ + ".partial-" + std::to_string(getpid());
  std::error_code ec;
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec) || ec) {
    throw InputError(final_, 0, "-o", "cannot create " + staging_ + ": " + ec.message());
  }
  RegisterScratchDirectory(staging_);  // removed even when a signal ends the process
}

StagedOutput::~StagedOutput() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
  UnregisterScratchDirectory(staging_);
}

void StagedOutput::Commit() {
  std::ofstream(fs::path(staging_) / kOutputMarker) << "lifelong output directory\n";
  std::error_code ec;
  if (fs::exists(final_, ec)) {
    CheckReplaceableOutput(final_);  // it may have changed while the run went on
    if (renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, final_.c_str(), RENAME_EXCHANGE) != 0) {
      if (errno != EINVAL && errno != ENOSYS) {
        throw std::runtime_error("cannot put " + staging_ + " in place of " + final_ + ": " +
                                 std::strerror(errno));
      }
      // No atomic exchange on this filesystem: two renames, the old result kept until the
      // new one is in place.
      const std::string old = final_ + ".old-" + std::to_string(getpid());
      if (std::rename(final_.c_str(), old.c_str()) != 0 ||
          std::rename(staging_.c_str(), final_.c_str()) != 0) {
        std::rename(old.c_str(), final_.c_str());
        throw std::runtime_error("cannot rename " + staging_ + " to " + final_ + ": " +
                                 std::strerror(errno));
      }
      committed_ = true;
      fs::remove_all(old, ec);
      return;
    }
  } else if (std::rename(staging_.c_str(), final_.c_str()) != 0) {
    throw std::runtime_error("cannot rename " + staging_ + " to " + final_ + ": " +
                             std::strerror(errno));
  }
  committed_ = true;
  fs::remove_all(staging_, ec);  // now the previous result
}

}  // namespace lifelong::eval
