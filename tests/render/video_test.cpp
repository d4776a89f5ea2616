// eval::OpenVideoSink's sink writes PNG frames and an mp4; eval::MakeScene places rays by
// hand-checked geometry. Skips when no GL backend can be created, and the mp4 part when OpenCV has
// no 'mp4v' writer.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "eval/figures/video.hpp"
#include "eval/video/video_sink.hpp"
#include "io/atomic_file.hpp"
#include "render/offscreen_renderer.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("lifelong_video_test_" + name);
  fs::remove_all(dir);
  return dir;
}

render::Scene SmallScene() {
  LaserScan scan;
  scan.angle_min_rad = 0.0;
  scan.angle_increment_rad = 0.5;
  scan.ranges_m = {3.0f, 2.0f, 100.0f};  // the third is no return
  scan.stamp_s = 1.5;
  OccupancyGrid map;
  map.width = map.height = 4;
  map.p_occ.assign(16, 0.0f);
  return MakeScene({{0, 5, 10, 5}}, Pose2(1, 1, 0), scan,
                   {MakePanel("standard", map, {}, {}, Pose2(1, 1, 0), 3)});
}

TEST(MakeSceneTest, RaysEndAtTheReturnsInTheWorldFrame) {
  LaserScan scan;
  scan.angle_min_rad = 0.0;
  scan.angle_increment_rad = 1.5707963267948966;
  scan.ranges_m = {2.0f, 1.0f, 0.0f};  // 0: no return
  scan.T_robot_laser = Pose2(0.5, 0.0, 0.0);
  // Robot at (1, 2) facing +y: the laser sits at (1, 2.5); beam 0 points along +y,
  // beam 1 along -x.
  const render::Scene scene = MakeScene({}, Pose2(1, 2, 1.5707963267948966), scan, {});
  ASSERT_EQ(scene.rays.size(), 2u);
  EXPECT_NEAR(scene.rays[0].x0, 1.0, 1e-9);
  EXPECT_NEAR(scene.rays[0].y0, 2.5, 1e-9);
  EXPECT_NEAR(scene.rays[0].x1, 1.0, 1e-9);
  EXPECT_NEAR(scene.rays[0].y1, 4.5, 1e-9);
  EXPECT_NEAR(scene.rays[1].x1, 0.0, 1e-9);
  EXPECT_NEAR(scene.rays[1].y1, 2.5, 1e-9);
  EXPECT_EQ(scene.world_caption, "t 0.0 s");
}

TEST(VideoSinkTest, RejectsOptionsWithoutOutputOrWithZeroStride) {
  VideoOptions options;
  EXPECT_THROW(OpenVideoSink(options), InputError);
  options.frames_dir = TempDir("bad").string();
  options.stride = 0;
  EXPECT_THROW(OpenVideoSink(options), InputError);
}

TEST(VideoSinkTest, WritesThreePngFramesAndAnMp4) {
  const fs::path dir = TempDir("frames");
  VideoOptions options;
  options.frames_dir = (dir / "frames").string();
  options.video_path = (dir / "run.mp4").string();
  options.stride = 5;
  options.width = 320;
  options.height = 180;
  std::unique_ptr<FrameSink> sink;
  try {
    sink = OpenVideoSink(options);
  } catch (const render::RenderError& e) {
    GTEST_SKIP() << "no GL backend here: " << e.what();
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find("mp4v") == std::string::npos) throw;
    options.video_path.clear();  // OpenCV without an mp4 writer: frames only
    sink = OpenVideoSink(options);
  }
  const render::Scene scene = SmallScene();
  int added = 0;
  for (int obs = 0; obs < 15; ++obs) {
    if (sink->Wants(obs)) sink->AddFrame(scene), ++added;
  }
  sink->Close();
  EXPECT_EQ(added, 3);  // observations 0, 5, 10
  EXPECT_EQ(sink->frames(), 3);
  for (const char* name : {"frame_000000.png", "frame_000001.png", "frame_000002.png"}) {
    const cv::Mat png = cv::imread((dir / "frames" / name).string());
    ASSERT_FALSE(png.empty()) << name;
    EXPECT_EQ(png.cols, 320);
    EXPECT_EQ(png.rows, 180);
  }
  EXPECT_FALSE(fs::exists(dir / "frames" / "frame_000003.png"));
  if (options.video_path.empty()) GTEST_SKIP() << "OpenCV has no 'mp4v' writer; mp4 not checked";
  cv::VideoCapture video(options.video_path);
  ASSERT_TRUE(video.isOpened());
  EXPECT_EQ(static_cast<int>(video.get(cv::CAP_PROP_FRAME_COUNT)), 3);
  cv::Mat frame;
  ASSERT_TRUE(video.read(frame));
  EXPECT_EQ(frame.cols, 320);
}

// The mp4 grows under its temporary name, appears whole on Close, and a run that fails
// (the sink destroyed while an exception unwinds) leaves neither it nor the temporary.
TEST(VideoSinkTest, TheVideoAppearsOnCloseAndNotAfterAFailedRun) {
  const fs::path dir = TempDir("atomic");
  VideoOptions options;
  options.video_path = (dir / "run.mp4").string();
  options.stride = 1;
  options.width = 64;
  options.height = 48;
  std::unique_ptr<FrameSink> sink;
  try {
    sink = OpenVideoSink(options);
  } catch (const render::RenderError& e) {
    GTEST_SKIP() << "no GL backend here: " << e.what();
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find("mp4v") == std::string::npos) throw;
    GTEST_SKIP() << "OpenCV has no 'mp4v' writer";
  }
  const std::string tmp = io::TempPathFor(options.video_path);
  sink->AddFrame(SmallScene());
  EXPECT_FALSE(fs::exists(options.video_path));
  EXPECT_TRUE(fs::exists(tmp));
  sink->Close();
  EXPECT_TRUE(fs::exists(options.video_path));
  EXPECT_FALSE(fs::exists(tmp));

  const fs::path failed = dir / "failed.mp4";
  options.video_path = failed.string();
  EXPECT_THROW(
      {
        const std::unique_ptr<FrameSink> doomed = OpenVideoSink(options);
        doomed->AddFrame(SmallScene());
        throw std::runtime_error("the run failed");
      },
      std::runtime_error);
  EXPECT_FALSE(fs::exists(failed));
  EXPECT_FALSE(fs::exists(io::TempPathFor(failed.string())));
}

TEST(VideoSinkTest, UnwritableFramesDirectoryNamesThePath) {
  const fs::path dir = TempDir("blocked");
  fs::create_directories(dir);
  std::ofstream(dir / "file") << "x";  // a file where the directory should go
  VideoOptions options;
  options.frames_dir = (dir / "file" / "frames").string();
  try {
    OpenVideoSink(options);
    FAIL() << "expected an exception";
  } catch (const render::RenderError& e) {
    GTEST_SKIP() << "no GL backend here: " << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(options.frames_dir), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lifelong::eval
