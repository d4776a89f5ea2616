#include "eval/figures/trajectory_figure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "eval/figures/draw.hpp"
#include "eval/figures/mode_colors.hpp"
#include "types/image.hpp"

namespace lifelong::eval {
namespace {

cv::Scalar Bgr(const render::Rgb& c) { return cv::Scalar(c.b, c.g, c.r); }

// 1, 2 or 5 times a power of ten, about a fifth of `span`.
double NiceLength(double span) {
  const double target = span / 5.0;
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * p <= target) return m * p;
  }
  return p;
}

}  // namespace

void WriteTrajectoryFigure(const std::string& path, const std::vector<Pose2>& reference,
                           const std::string& reference_name,
                           const std::vector<AlignedTrack>& tracks, int max_side_px) {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  auto grow = [&](const std::vector<Pose2>& poses) {
    for (const Pose2& p : poses) {
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    }
  };
  grow(reference);
  for (const AlignedTrack& t : tracks) grow(t.poses);
  if (!(x1 >= x0)) x0 = y0 = 0.0, x1 = y1 = 1.0;
  const double span = std::max({x1 - x0, y1 - y0, 1.0});
  const int margin = 40, key_h = 22 * (static_cast<int>(tracks.size()) + 1) + 10;
  const double px_per_m = (max_side_px - 2.0 * margin) / span;
  const int w = static_cast<int>(std::ceil((x1 - x0) * px_per_m)) + 2 * margin;
  const int h = static_cast<int>(std::ceil((y1 - y0) * px_per_m)) + 2 * margin + key_h;
  cv::Mat img(h, std::max(w, 320), CV_8UC3, cv::Scalar(255, 255, 255));
  auto pixel = [&](const Pose2& p) {  // y up
    return cv::Point(static_cast<int>(std::lround(margin + (p.x - x0) * px_per_m)),
                     static_cast<int>(std::lround(h - margin - (p.y - y0) * px_per_m)));
  };
  auto draw = [&](const std::vector<Pose2>& poses, const cv::Scalar& colour, int thickness) {
    std::vector<cv::Point> line;
    for (const Pose2& p : poses) line.push_back(pixel(p));
    if (line.size() > 1) cv::polylines(img, line, false, colour, thickness, cv::LINE_AA);
  };
  draw(reference, cv::Scalar(0, 0, 0), 3);
  for (const AlignedTrack& t : tracks) draw(t.poses, Bgr(ModeColour(t.mode)), 1);
  // Key, top left: the reference, then the modes in order.
  int y = 22;
  auto key = [&](const std::string& text, const cv::Scalar& colour, int thickness) {
    cv::line(img, {12, y - 5}, {42, y - 5}, colour, thickness, cv::LINE_AA);
    cv::putText(img, text, {50, y}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1,
                cv::LINE_AA);
    y += 22;
  };
  key(reference_name, cv::Scalar(0, 0, 0), 3);
  for (const AlignedTrack& t : tracks) {
    key(t.mode + " (aligned by its ATE)", Bgr(ModeColour(t.mode)), 2);
  }
  // Scale bar, bottom left.
  const double bar_m = NiceLength(span);
  const int bar_px = static_cast<int>(std::lround(bar_m * px_per_m));
  cv::line(img, {margin, h - 15}, {margin + bar_px, h - 15}, cv::Scalar(0, 0, 0), 2);
  char label[32];
  std::snprintf(label, sizeof(label), "%g m", bar_m);
  cv::putText(img, label, {margin + bar_px + 8, h - 10}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  Image out;  // RGB for the libpng writer (OpenCV's codecs stay out of the run)
  out.width = img.cols;
  out.height = img.rows;
  out.rgb.resize(static_cast<std::size_t>(img.cols) * static_cast<std::size_t>(img.rows) * 3u);
  cv::Mat rgb(img.rows, img.cols, CV_8UC3, out.rgb.data());
  cv::cvtColor(img, rgb, cv::COLOR_BGR2RGB);
  WritePng(path, out);
}

}  // namespace lifelong::eval
