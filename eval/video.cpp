#include "eval/video.hpp"

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "eval/draw.hpp"
#include "io/atomic_file.hpp"
#include "render/offscreen_renderer.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

// The rendered image with its labels drawn (Hershey simplex, anti-aliased; the grey text
// blends each channel alike, so drawing it before or after the RGB -> BGR swap is the same).
Image WithLabels(render::Frame frame) {
  Image& image = frame.image;
  cv::Mat rgb(image.height, image.width, CV_8UC3, image.rgb.data());
  for (const render::TextLabel& label : frame.labels) {
    const double scale = label.height_px / 22.0;  // simplex capitals are ~22 px at scale 1
    cv::putText(rgb, label.text, {label.x_px, label.baseline_px}, cv::FONT_HERSHEY_SIMPLEX, scale,
                cv::Scalar(30, 30, 30), 1, cv::LINE_AA);
  }
  return std::move(frame.image);
}

void CreateDirectories(const fs::path& dir, const std::string& what) {
  if (dir.empty()) return;
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir))
    throw std::runtime_error("cannot create " + what + " '" + dir.string() +
                             "': " + (error ? error.message() : "not a directory"));
}

void Check(const VideoOptions& o) {
  const auto bad = [](const std::string& field, const std::string& what) {
    return InputError("video options", 0, field, what);
  };
  if (o.video_path.empty() && o.frames_dir.empty())
    throw bad("video_path", "neither a video file nor a frames directory given");
  if (o.stride < 1) throw bad("stride", "must be >= 1, got " + std::to_string(o.stride));
  if (o.width < 16 || o.width > 8192 || o.height < 16 || o.height > 8192)
    throw bad("width", "frame size must be 16..8192 pixels");
  if (!(o.fps > 0.0 && o.fps <= 1000.0)) throw bad("fps", "must be in (0, 1000]");
}

render::RendererOptions RendererFor(render::BackendChoice backend) {
  render::RendererOptions options;
  options.backend = backend;
  return options;
}

}  // namespace

struct VideoSink::Impl {
  VideoOptions options;
  render::OffscreenRenderer renderer;
  cv::VideoWriter writer;
  std::vector<render::Bounds> views;  // grow over the run, so the picture does not jump
  int frames = 0;
  bool closed = false;
  std::string video_tmp;  // the mp4 is written here and renamed onto video_path by Close
  int exceptions_at_start = std::uncaught_exceptions();
};

VideoSink::VideoSink(const VideoOptions& options) {
  Check(options);
  auto renderer = render::OffscreenRenderer::Create(options.width, options.height,
                                                    RendererFor(options.backend));
  impl_ = std::make_unique<Impl>(
      Impl{options, std::move(renderer), {}, {}, 0, false, {}, std::uncaught_exceptions()});
  CreateDirectories(options.frames_dir, "frames directory");
  if (!options.video_path.empty()) {
    CreateDirectories(fs::path(options.video_path).parent_path(), "video directory");
    impl_->video_tmp = io::TempPathFor(options.video_path);  // ".mp4" kept for the container
    impl_->writer.open(impl_->video_tmp, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), options.fps,
                       cv::Size(options.width, options.height), true);
    if (!impl_->writer.isOpened())
      throw std::runtime_error("cannot open video '" + options.video_path +
                               "' for writing (OpenCV has no mp4v writer, or the path is bad)");
  }
}

VideoSink::~VideoSink() {
  if (std::uncaught_exceptions() > impl_->exceptions_at_start) {  // a failed run: no video
    impl_->writer.release();
    if (!impl_->video_tmp.empty()) std::remove(impl_->video_tmp.c_str());
    return;
  }
  try {
    Close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw
  }
}

bool VideoSink::Wants(int observation_index) const {
  return observation_index >= 0 && observation_index % impl_->options.stride == 0;
}

void VideoSink::AddFrame(const render::Scene& scene) {
  Impl& m = *impl_;
  if (m.closed) throw std::logic_error("VideoSink::AddFrame after Close");
  const std::vector<render::Bounds> now = render::ViewBounds(scene);
  if (m.views.size() != now.size()) m.views.assign(now.size(), render::Bounds{});
  for (std::size_t i = 0; i < now.size(); ++i) m.views[i].Extend(now[i]);
  Image image =
      WithLabels(scene.view ? m.renderer.Render(scene) : m.renderer.Render(scene, m.views));
  if (m.writer.isOpened()) {
    cv::Mat bgr;
    cv::cvtColor(cv::Mat(image.height, image.width, CV_8UC3, image.rgb.data()), bgr,
                 cv::COLOR_RGB2BGR);
    m.writer.write(bgr);
  }
  if (!m.options.frames_dir.empty()) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%06d.png", m.frames);
    WritePng((fs::path(m.options.frames_dir) / name).string(), image);
  }
  ++m.frames;
}

void VideoSink::Close() {
  if (impl_->closed) return;
  impl_->closed = true;
  const bool opened = impl_->writer.isOpened();
  impl_->writer.release();
  if (opened) io::CommitTempFile(impl_->video_tmp, impl_->options.video_path);
}

int VideoSink::frames() const { return impl_->frames; }
std::string VideoSink::backend_name() const { return impl_->renderer.backend_name(); }

render::Panel MakePanel(const std::string& title, const OccupancyGrid& map,
                        const slam::PoseGraph& graph, const slam::Values& values,
                        const Pose2& robot_estimate, int observation) {
  render::Panel panel;
  panel.title = title;
  panel.map = map;
  GraphOverlay overlay = MakeGraphOverlay(graph, values);
  panel.nodes = std::move(overlay.nodes);
  panel.edges = std::move(overlay.edges);
  panel.robot_estimate = robot_estimate;
  panel.observation = observation;
  panel.node_count = graph.NumNodes();
  panel.edge_count = graph.NumEdgesForGamma();
  return panel;
}

render::Scene MakeScene(const std::vector<Segment>& walls, const Pose2& T_world_robot,
                        const LaserScan& scan, std::vector<render::Panel> panels) {
  render::Scene scene;
  scene.walls = walls;
  scene.robot_true = T_world_robot;
  const Pose2 T_world_laser = T_world_robot * scan.T_robot_laser;
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    if (!scan.IsReturn(i)) continue;
    const double r = scan.ranges_m[i], a = scan.Bearing(i);
    double x = 0.0, y = 0.0;
    T_world_laser.Apply(r * std::cos(a), r * std::sin(a), &x, &y);
    scene.rays.push_back({T_world_laser.x, T_world_laser.y, x, y});
  }
  char caption[48];
  std::snprintf(caption, sizeof(caption), "t %.1f s", scan.stamp_s);
  scene.world_caption = caption;
  scene.panels = std::move(panels);
  return scene;
}

std::string WriteScenePng(const std::string& path, const render::Scene& scene, int width,
                          int height) {
  auto renderer = render::OffscreenRenderer::Create(width, height);
  CreateDirectories(fs::path(path).parent_path(), "directory");
  WritePng(path, WithLabels(renderer.Render(scene)));
  return renderer.backend_name();
}

}  // namespace lifelong::eval
