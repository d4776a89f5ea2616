// Checks of output paths made before any work, so that a long job never ends in "cannot
// write": each throws InputError naming the path and the option it came from (exit 2).
#pragma once

#include <string>

namespace lifelong::io {

/// A file can be written at `path`: not empty, not a directory, its directory can be made
/// and written in (probed with a file that is removed again). `flag` names the option.
void CheckWritableFile(const std::string& path, const std::string& flag = "-o");

/// A directory that can be made or written in: itself when it exists, else its nearest
/// existing ancestor, which must be a directory one may write in. Not empty.
void CheckWritableDirectory(const std::string& path, const std::string& flag);

}  // namespace lifelong::io
