// Videos of runs (issue #7). A run hands a FrameSink one render::Scene every `stride`
// observations; the sink renders it offscreen and writes the frames as an mp4 and/or as PNG
// files DIR/frame_000000.png, ... (eval/video/video_sink.hpp). The sink lives in its own library,
// with OpenGL and OpenCV's video writer, so that a run without --video loads neither:
// `lifelong` loads the module liblifelong_video.so only when a video is asked for
// (apps/video_module.hpp). The MakePanel / MakeScene helpers build the scene from the
// mapper's plain data.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "render/gl_context.hpp"
#include "render/scene.hpp"
#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "slam/graph/pose_graph.hpp"
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

/// Where a run's frames go.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// True for the observations to render (index % stride == 0).
  virtual bool Wants(int observation_index) const = 0;
  /// Renders and writes one frame. Throws std::runtime_error naming the file on failure.
  virtual void AddFrame(const render::Scene& scene) = 0;
  /// Finishes the video and renames it into place; later AddFrame calls throw.
  virtual void Close() = 0;
  virtual int frames() const = 0;
  virtual std::string backend_name() const = 0;
};

/// Makes a sink for the options (eval::OpenVideoSink, or the module's), throwing as it does.
using FrameSinkOpener = std::function<std::unique_ptr<FrameSink>(const VideoOptions&)>;

/// One mode's panel: the graph at `values` (a clique is drawn as marginal edges from its
/// root, as eval::MakeGraphOverlay does), its counts, the map and the pose estimate.
render::Panel MakePanel(const std::string& title, const OccupancyGrid& map,
                        const slam::PoseGraph& graph, const slam::Values& values,
                        const Pose2& robot_estimate, int observation);

/// The world view: walls, the robot at T_world_robot, and a ray to every return of `scan`
/// (from T_world_robot * scan.T_robot_laser); the caption gives the scan's time.
render::Scene MakeScene(const std::vector<Segment>& walls, const Pose2& T_world_robot,
                        const LaserScan& scan, std::vector<render::Panel> panels);

}  // namespace lifelong::eval
