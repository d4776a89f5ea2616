// `lifelong run --frames/--video` through the module liblifelong_video.so, which a run
// without them never loads (apps/video_module.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_lifelong.hpp"

namespace {

namespace fs = std::filesystem;

using lifelong::test::Lifelong;
using lifelong::test::Result;

fs::path Fresh(const std::string& name) { return lifelong::test::FreshPath("video_cli_", name); }

TEST(VideoCli, FramesAreWrittenThroughTheVideoModule) {
  const fs::path dir = Fresh("frames");
  const Result r = Lifelong("run " + std::string(LIFELONG_SOURCE_DIR) +
                            "/scenarios/corridor_3.yaml --modes standard --stride 10 --frames " +
                            (dir / "frames").string() + " -o " + (dir / "run").string());
  if (r.code != 0 && r.output.find("no offscreen OpenGL") != std::string::npos) {
    GTEST_SKIP() << "no GL backend here: " << r.output;
  }
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("rendering with"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "frames" / "frame_000000.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "frames" / "frame_000001.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "run" / "standard" / "map.png"));
}

TEST(VideoCli, AMissingVideoModuleIsNamedAndTheRunLeavesNothing) {
  // A copy of the program and the commands module, without the video module beside them.
  const fs::path bin = Fresh("bin");
  fs::create_directories(bin);
  const fs::path built = fs::path(LIFELONG_BIN).parent_path();
  fs::copy_file(LIFELONG_BIN, bin / "lifelong");
  fs::copy_file(built / "liblifelong_commands.so", bin / "liblifelong_commands.so");
  const fs::path out = Fresh("missing") / "run";
  const std::string cmd = (bin / "lifelong").string() + " run " + LIFELONG_SOURCE_DIR +
                          "/scenarios/corridor_3.yaml --modes standard --frames " +
                          (out.parent_path() / "frames").string() + " -o " + out.string() + " 2>&1";
  std::string output;
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof(buf), p)) > 0;) output.append(buf, n);
  const int status = pclose(p);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_NE(WEXITSTATUS(status), 0) << output;
  EXPECT_NE(output.find("liblifelong_video.so"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
