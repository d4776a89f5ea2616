// The frame sink of eval/figures/video.hpp: renders each scene with render::OffscreenRenderer (EGL,
// else OSMesa; no display needed) and writes the frames as an mp4 (cv::VideoWriter, fourcc
// 'mp4v') and/or as PNG files. Titles and counters are drawn with cv::putText. Every file
// is written atomically (io/atomic_file.hpp): the mp4 grows under a temporary name and is
// renamed into place by Close; a sink destroyed by an exception leaves no video.
// In the library lifelong_video, linked into the module liblifelong_video.so (and tests).
#pragma once

#include <memory>
#include <string>

#include "eval/figures/video.hpp"

namespace lifelong::eval {

/// Creates the renderer, the frames directory and the video file. Throws InputError for
/// bad options (no output, stride < 1, size or fps out of range), render::RenderError when
/// no GL backend works, std::runtime_error naming the path when a file or directory cannot
/// be created. Destroying the sink closes it (FrameSink::Close), unless that happens for an
/// exception: then the video is discarded.
std::unique_ptr<FrameSink> OpenVideoSink(const VideoOptions& options);

}  // namespace lifelong::eval
