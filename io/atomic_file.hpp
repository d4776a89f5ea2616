// Writing a file so that it is never seen half written: the bytes go to a temporary file
// beside the target, which is renamed onto it only once it is complete (rename(2) replaces
// the target in one step). A failed write leaves the previous file, if any, untouched and
// removes the temporary file. This guards against failures of the process (an exception, a
// full disk, a kill), not against power loss: nothing is fsync'ed.
//
// Every file lifelong writes goes through here: logs, trajectories, graphs, maps, PNGs,
// CSVs, plot data, summary.json and report.html.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace lifelong::io {

/// The name `path` is written under until it is complete: beside it, with the same
/// extension, so that writers choosing a format by the name (cv::imwrite, gnuplot, gzip
/// by ".gz") still can: "dir/map.tmp.png" for "dir/map.png", "dir/log.clf.tmp.gz" for
/// "dir/log.clf.gz", "dir/name.tmp" for a name without an extension.
std::string TempPathFor(const std::string& path);

/// Renames the finished temporary file `tmp_path` onto `path`. On failure removes
/// `tmp_path` and throws InputError naming `path`.
void CommitTempFile(const std::string& tmp_path, const std::string& path);

/// Writes `path` through TempPathFor(path): `write(tmp_path)` must create the whole file
/// there and return true, then it is renamed onto `path`. When `write` returns false or
/// throws, or the rename fails, the temporary file is removed and `path` is left as it
/// was; throws InputError naming `path` (or lets what `write` threw pass).
void WriteThroughTempFile(const std::string& path,
                          const std::function<bool(const std::string& tmp_path)>& write);

/// Writes `bytes` to `path` atomically, as above. Throws InputError naming `path` when the
/// file cannot be written (e.g. no such directory, a full disk).
void WriteFileAtomically(const std::string& path, std::string_view bytes);

}  // namespace lifelong::io
