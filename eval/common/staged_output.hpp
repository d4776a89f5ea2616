// All-or-nothing output directories (DESIGN.md "Results are all or nothing"). A run writes
// into a staging directory beside DIR (`DIR.partial-<pid>`); Commit() swaps it into place
// with one atomic rename (renameat2 RENAME_EXCHANGE, or rename when DIR does not exist)
// and removes the previous result. A run that fails or is interrupted never commits: the
// destructor removes the staging directory and DIR keeps the previous complete result.
//
// DIR is replaced only when it is absent, empty, or an earlier lifelong result (it holds
// the marker file `.lifelong-output`, or `summary.json` / `report.html` from versions
// before the marker): `-o ~` must never delete a home directory.
#pragma once

#include <string>

namespace lifelong::eval {

/// Name of the marker file every committed output directory holds.
inline constexpr const char* kOutputMarker = ".lifelong-output";

class StagedOutput {
 public:
  /// Checks that `final_dir` may be replaced and that its parent is writable, and creates
  /// the staging directory. Throws lifelong::InputError (field "-o") when not.
  explicit StagedOutput(std::string final_dir);
  /// Removes the staging directory unless committed.
  ~StagedOutput();
  StagedOutput(const StagedOutput&) = delete;
  StagedOutput& operator=(const StagedOutput&) = delete;

  /// Where the run writes its files.
  const std::string& path() const { return staging_; }
  const std::string& final_dir() const { return final_; }

  /// Writes the marker, puts the staging directory in place of final_dir and removes the
  /// previous result. Throws std::runtime_error when the swap fails (final_dir unchanged).
  void Commit();

 private:
  std::string final_;
  std::string staging_;
  bool committed_ = false;
};

/// Throws lifelong::InputError (field "-o") when `dir` exists and is neither empty nor an
/// earlier lifelong output, or when its parent directory cannot be created or written.
void CheckReplaceableOutput(const std::string& dir);

}  // namespace lifelong::eval
