// All-or-nothing output directories (eval/common/staged_output.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "eval/common/staged_output.hpp"
#include "sensor/input_error.hpp"
#include "test_files.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

fs::path Fresh(const std::string& name) {
  const fs::path p = fs::path(::testing::TempDir()) / ("staged_" + name);
  fs::remove_all(p);
  return p;
}

void Write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

TEST(StagedOutput, CommitReplacesTheWholeEarlierResult) {
  const fs::path dir = Fresh("replace");
  fs::create_directories(dir / "pruned");
  Write(dir / "summary.json", "old");
  Write(dir / "pruned" / "timeline.csv", "old");
  {
    StagedOutput out(dir.string());
    EXPECT_NE(out.path(), dir.string());
    Write(fs::path(out.path()) / "summary.json", "new");
    EXPECT_EQ(ReadFileText(dir / "summary.json"), "old");  // untouched until the commit
    out.Commit();
  }
  EXPECT_EQ(ReadFileText(dir / "summary.json"), "new");
  EXPECT_FALSE(fs::exists(dir / "pruned"));  // nothing of the earlier run is left
  EXPECT_TRUE(fs::exists(dir / kOutputMarker));
  for (const auto& e : fs::directory_iterator(dir.parent_path())) {
    EXPECT_EQ(e.path().filename().string().find("staged_replace."), std::string::npos) << e.path();
  }
}

TEST(StagedOutput, WithoutCommitTheEarlierResultStaysAndTheStagingGoes) {
  const fs::path dir = Fresh("abort");
  fs::create_directories(dir);
  Write(dir / "summary.json", "old");
  std::string staging;
  {
    StagedOutput out(dir.string());
    staging = out.path();
    Write(fs::path(staging) / "summary.json", "partial");
  }  // e.g. an exception or Ctrl-C unwound the run
  EXPECT_EQ(ReadFileText(dir / "summary.json"), "old");
  EXPECT_FALSE(fs::exists(staging));
}

TEST(StagedOutput, ANewDirectoryIsCreatedOnCommit) {
  const fs::path dir = Fresh("new") / "sub";
  StagedOutput out((dir.string() + "/"));  // a trailing slash names the same directory
  Write(fs::path(out.path()) / "summary.json", "new");
  out.Commit();
  EXPECT_EQ(ReadFileText(dir / "summary.json"), "new");
}

TEST(StagedOutput, RefusesADirectoryThatIsNotAnOutput) {
  const fs::path dir = Fresh("foreign");
  fs::create_directories(dir);
  Write(dir / "thesis.tex", "precious");
  EXPECT_THROW(StagedOutput{dir.string()}, InputError);
  EXPECT_EQ(ReadFileText(dir / "thesis.tex"), "precious");
  EXPECT_THROW(CheckReplaceableOutput("."), InputError);
  EXPECT_THROW(CheckReplaceableOutput("/"), InputError);
}

TEST(StagedOutput, RefusesAFile) {
  const fs::path file = Fresh("file");
  Write(file, "x");
  EXPECT_THROW(CheckReplaceableOutput(file.string()), InputError);
}

}  // namespace
}  // namespace lifelong::eval
