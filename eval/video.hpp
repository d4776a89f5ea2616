// Videos of runs (issue #7): eval::VideoSink renders a render::Scene every `stride`
// observations with render::OffscreenRenderer (EGL, else OSMesa; no display needed) and
// writes the frames as an mp4 (cv::VideoWriter, fourcc 'mp4v') and/or as PNG files
// DIR/frame_000000.png, ... . Titles and counters are drawn with cv::putText. Every file is
// written atomically (io/atomic_file.hpp): the mp4 grows under a temporary name and is
// renamed into place by Close; a sink destroyed by an exception leaves no video.
// Nothing here runs unless a VideoSink is made: a run without --video pays nothing.
// The MakePanel / MakeScene helpers build the scene from the mapper's plain data.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/gl_context.hpp"
#include "render/scene.hpp"
#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "slam/pose_graph.hpp"
#include "types/occupancy_grid.hpp"
#include "types/segment.hpp"

namespace lifelong::eval {

struct VideoOptions {
  std::string video_path;  ///< .mp4 file to write; empty: no video
  std::string frames_dir;  ///< directory for PNG frames (created); empty: no frames
  int stride = 10;         ///< render observations 0, stride, 2 stride, ... (>= 1)
  int width = 1280;        ///< frame width, pixels (16..8192)
  int height = 720;        ///< frame height, pixels (16..8192)
  double fps = 15.0;       ///< frames per second of the video
  render::BackendChoice backend = render::BackendChoice::kAuto;
};

class VideoSink {
 public:
  /// Creates the renderer, the frames directory and the video file. Throws InputError
  /// for bad options (no output, stride < 1, size or fps out of range), render::RenderError
  /// when no GL backend works, std::runtime_error naming the path when a file or directory
  /// cannot be created.
  explicit VideoSink(const VideoOptions& options);
  ~VideoSink();
  VideoSink(const VideoSink&) = delete;
  VideoSink& operator=(const VideoSink&) = delete;

  /// True for the observations to render (index % stride == 0).
  bool Wants(int observation_index) const;
  /// Renders and writes one frame. Throws std::runtime_error naming the file on failure.
  void AddFrame(const render::Scene& scene);
  /// Finishes the video and renames it into place; later AddFrame calls throw. Called by
  /// the destructor, unless that runs for an exception (then the video is discarded).
  void Close();

  int frames() const;
  std::string backend_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One mode's panel: the graph at `values` (a clique is drawn as marginal edges from its
/// root, as eval::MakeGraphOverlay does), its counts, the map and the pose estimate.
render::Panel MakePanel(const std::string& title, const OccupancyGrid& map,
                        const slam::PoseGraph& graph, const slam::Values& values,
                        const Pose2& robot_estimate, int observation);

/// The world view: walls, the robot at T_world_robot, and a ray to every return of `scan`
/// (from T_world_robot * scan.T_robot_laser); the caption gives the scan's time.
render::Scene MakeScene(const std::vector<Segment>& walls, const Pose2& T_world_robot,
                        const LaserScan& scan, std::vector<render::Panel> panels);

/// Renders one scene (e.g. a run's final state) and writes it as a PNG; returns the
/// backend used. Throws as VideoSink does.
std::string WriteScenePng(const std::string& path, const render::Scene& scene, int width = 1280,
                          int height = 720);

}  // namespace lifelong::eval
