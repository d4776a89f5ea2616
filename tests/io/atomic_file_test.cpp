// The one atomic writer (io/atomic_file.hpp) and the io writers built on it: a write that
// fails part-way (a file-size limit, as a full disk), a writer that gives up, or a rename
// that fails leaves the previous file as it was and no temporary file behind.
#include "io/atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "io/carmen_log.hpp"
#include "io/graph_file.hpp"
#include "io/map_file.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"
#include "tests/io/file_size_limit.hpp"

namespace lifelong::io {
namespace {

namespace fs = std::filesystem;

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("io_atomic_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Only `keep` in `dir`: no temporary file left behind.
void ExpectOnlyFile(const fs::path& dir, const fs::path& keep) {
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path(), keep) << "left behind: " << entry.path();
}

TEST(TempPathFor, KeepsTheExtensionBesideTheTarget) {
  EXPECT_EQ(TempPathFor("dir/map.png"), "dir/map.tmp.png");
  EXPECT_EQ(TempPathFor("dir/log.clf.gz"), "dir/log.clf.tmp.gz");
  EXPECT_EQ(TempPathFor("/a/b/summary.json"), "/a/b/summary.tmp.json");
  EXPECT_EQ(TempPathFor("name"), "name.tmp");
}

TEST(WriteFileAtomically, WritesAndReplacesWhole) {
  const fs::path dir = FreshDir("replace");
  const fs::path path = dir / "a.txt";
  WriteFileAtomically(path.string(), "first\n");
  EXPECT_EQ(ReadBytes(path), "first\n");
  WriteFileAtomically(path.string(), std::string("se\0cond", 7));
  EXPECT_EQ(ReadBytes(path), std::string("se\0cond", 7));
  ExpectOnlyFile(dir, path);
}

TEST(WriteFileAtomically, FailedWriteKeepsThePreviousFileAndNoTemporary) {
  const fs::path dir = FreshDir("full");
  const fs::path path = dir / "summary.json";
  WriteFileAtomically(path.string(), "previous\n");
  const std::string big(1 << 20, 'x');  // 1 MiB against a 64 KiB limit
  {
    const testing::FileSizeLimit limit(64 * 1024);
    EXPECT_THROW(WriteFileAtomically(path.string(), big), InputError);
  }
  EXPECT_EQ(ReadBytes(path), "previous\n");
  ExpectOnlyFile(dir, path);
  WriteFileAtomically(path.string(), big);  // and it works again without the limit
  EXPECT_EQ(ReadBytes(path).size(), big.size());
}

TEST(WriteFileAtomically, MissingDirectoryThrowsNamingThePath) {
  const fs::path path = FreshDir("missing") / "no_such_dir" / "x.csv";
  try {
    WriteFileAtomically(path.string(), "x");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
  }
  EXPECT_FALSE(fs::exists(path.parent_path()));
}

TEST(WriteThroughTempFile, WriterThatFailsOrThrowsLeavesThePreviousFile) {
  const fs::path dir = FreshDir("writer");
  const fs::path path = dir / "frame.png";
  WriteFileAtomically(path.string(), "previous");
  const auto partial = [](const std::string& tmp) {
    std::ofstream(tmp) << "half";
    return false;
  };
  EXPECT_THROW(WriteThroughTempFile(path.string(), partial), InputError);
  const auto throws = [](const std::string& tmp) -> bool {
    std::ofstream(tmp) << "half";
    throw std::runtime_error("encoder failed");
  };
  EXPECT_THROW(WriteThroughTempFile(path.string(), throws), std::runtime_error);
  EXPECT_EQ(ReadBytes(path), "previous");
  ExpectOnlyFile(dir, path);
}

TEST(WriteThroughTempFile, FailedRenameRemovesTheTemporary) {
  const fs::path dir = FreshDir("rename");
  const fs::path target = dir / "out";  // a non-empty directory: no file can replace it
  fs::create_directories(target / "inside");
  EXPECT_THROW(WriteFileAtomically(target.string(), "x"), InputError);
  EXPECT_TRUE(fs::is_directory(target / "inside"));
  ExpectOnlyFile(dir, target);
}

// The io writers: a graph, a trajectory, a map and a log cut short by the limit.
TEST(AtomicWriters, FailedWritesKeepThePreviousFiles) {
  const fs::path dir = FreshDir("writers");
  PoseFactors graph;
  Values values;
  std::vector<StampedPose> poses;
  for (int i = 0; i < 4000; ++i) {
    graph.nodes.push_back(i);
    values[i] = Pose2(0.5 * i, 0.0, 0.0);
    if (i > 0) graph.edges.push_back({i - 1, i, Pose2(0.5, 0.0, 0.0)});
    poses.push_back({0.1 * i, values[i]});
  }
  OccupancyGrid grid;
  grid.width = grid.height = 400;
  grid.p_occ.assign(400 * 400, 0.0f);
  const fs::path g2o = dir / "graph.g2o", tum = dir / "trajectory.tum", pgm = dir / "map.pgm";
  const fs::path clf = dir / "log.clf";
  for (const fs::path& p : {g2o, tum, pgm, clf}) WriteFileAtomically(p.string(), "previous");
  {
    const testing::FileSizeLimit limit(16 * 1024);  // each file needs more than that
    EXPECT_THROW(WriteG2o(g2o.string(), graph, values), InputError);
    EXPECT_THROW(WriteTum(tum.string(), poses), InputError);
    EXPECT_THROW(WritePgmMap(pgm.string(), grid), InputError);
    EXPECT_THROW(
        {
          CarmenWriter writer(clf.string());
          for (const StampedPose& p : poses) writer.WriteOdometry({p.stamp_s, p.T_world_robot});
          writer.Close();
        },
        InputError);
  }
  for (const fs::path& p : {g2o, tum, pgm, clf}) EXPECT_EQ(ReadBytes(p), "previous") << p;
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 4u);                   // map.yaml is written after map.pgm, so it never was
  WriteG2o(g2o.string(), graph, values);  // without the limit each writes in full
  EXPECT_EQ(ReadGraphFile(g2o.string()).factors.nodes.size(), 4000u);
}

}  // namespace
}  // namespace lifelong::io
