#include "eval/video/video_sink.hpp"

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "eval/figures/draw.hpp"
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

const VideoOptions& Checked(const VideoOptions& o) {
  const auto bad = [](const std::string& field, const std::string& what) {
    return InputError("video options", 0, field, what);
  };
  if (o.video_path.empty() && o.frames_dir.empty())
    throw bad("video_path", "neither a video file nor a frames directory given");
  if (o.stride < 1) throw bad("stride", "must be >= 1, got " + std::to_string(o.stride));
  if (o.width < 16 || o.width > 8192 || o.height < 16 || o.height > 8192)
    throw bad("width", "frame size must be 16..8192 pixels");
  if (!(o.fps > 0.0 && o.fps <= 1000.0)) throw bad("fps", "must be in (0, 1000]");
  return o;
}

render::RendererOptions RendererFor(render::BackendChoice backend) {
  render::RendererOptions options;
  options.backend = backend;
  return options;
}

class VideoFileSink final : public FrameSink {
 public:
  explicit VideoFileSink(const VideoOptions& options);
  ~VideoFileSink() override;
  VideoFileSink(const VideoFileSink&) = delete;
  VideoFileSink& operator=(const VideoFileSink&) = delete;
  bool Wants(int observation_index) const override;
  void AddFrame(const render::Scene& scene) override;
  void Close() override;
  int frames() const override { return frames_; }
  std::string backend_name() const override { return renderer_.backend_name(); }

 private:
  VideoOptions options_;
  render::OffscreenRenderer renderer_;
  cv::VideoWriter writer_;
  std::vector<render::Bounds> views_;  // grow over the run, so the picture does not jump
  int frames_ = 0;
  bool closed_ = false;
  std::string video_tmp_;  // the mp4 is written here and renamed onto video_path by Close
  int exceptions_at_start_ = std::uncaught_exceptions();
};

VideoFileSink::VideoFileSink(const VideoOptions& options)
    : options_(Checked(options)),
      renderer_(render::OffscreenRenderer::Create(options.width, options.height,
                                                  RendererFor(options.backend))) {
  CreateDirectories(options.frames_dir, "frames directory");
  if (!options.video_path.empty()) {
    CreateDirectories(fs::path(options.video_path).parent_path(), "video directory");
    video_tmp_ = io::TempPathFor(options.video_path);  // ".mp4" kept for the container
    writer_.open(video_tmp_, cv::VideoWriter::fourcc('m', 'p', '4', 'v'), options.fps,
                 cv::Size(options.width, options.height), true);
    if (!writer_.isOpened())
      throw std::runtime_error("cannot open video '" + options.video_path +
                               "' for writing (OpenCV has no mp4v writer, or the path is bad)");
  }
}

VideoFileSink::~VideoFileSink() {
  if (std::uncaught_exceptions() > exceptions_at_start_) {  // a failed run: no video
    writer_.release();
    if (!video_tmp_.empty()) std::remove(video_tmp_.c_str());
    return;
  }
  try {
    Close();
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw
  }
}

bool VideoFileSink::Wants(int observation_index) const {
  return observation_index >= 0 && observation_index % options_.stride == 0;
}

void VideoFileSink::AddFrame(const render::Scene& scene) {
  if (closed_) throw std::logic_error("FrameSink::AddFrame after Close");
  const std::vector<render::Bounds> now = render::ViewBounds(scene);
  if (views_.size() != now.size()) views_.assign(now.size(), render::Bounds{});
  for (std::size_t i = 0; i < now.size(); ++i) views_[i].Extend(now[i]);
  Image image = WithLabels(scene.view ? renderer_.Render(scene) : renderer_.Render(scene, views_));
  if (writer_.isOpened()) {
    cv::Mat bgr;
    cv::cvtColor(cv::Mat(image.height, image.width, CV_8UC3, image.rgb.data()), bgr,
                 cv::COLOR_RGB2BGR);
    writer_.write(bgr);
  }
  if (!options_.frames_dir.empty()) {
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%06d.png", frames_);
    WritePng((fs::path(options_.frames_dir) / name).string(), image);
  }
  ++frames_;
}

void VideoFileSink::Close() {
  if (closed_) return;
  closed_ = true;
  const bool opened = writer_.isOpened();
  writer_.release();
  if (opened) io::CommitTempFile(video_tmp_, options_.video_path);
}

}  // namespace

std::unique_ptr<FrameSink> OpenVideoSink(const VideoOptions& options) {
  return std::make_unique<VideoFileSink>(options);
}

}  // namespace lifelong::eval
