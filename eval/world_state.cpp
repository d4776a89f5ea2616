#include "eval/world_state.hpp"

#include <algorithm>
#include <cstddef>

#include <filesystem>
#include <memory>

#include "eval/simulation.hpp"
#include "io/segments_file.hpp"

namespace lifelong::eval {
namespace {

// The box's pose at t_s: its last move at or before t_s, else its initial pose.
sim::Box BoxAt(const sim::Box& box, double t_s) {
  sim::Box at = box;
  for (const sim::BoxMove& m : box.moves) {
    if (m.t_s > t_s) break;
    at.center = m.center;
    at.yaw_rad = m.yaw_rad;
  }
  return at;
}

std::vector<Segment> OutlineOf(const sim::Box& box) {
  sim::World one;
  one.boxes.push_back(box);
  return sim::BoxSegments(one);
}

bool SamePose(const sim::Box& a, const sim::Box& b) {
  return a.center.x == b.center.x && a.center.y == b.center.y && a.yaw_rad == b.yaw_rad;
}

}  // namespace

std::vector<Segment> WallsAt(const sim::World& world, double t_s) {
  std::vector<Segment> out = sim::WallSegments(world);
  for (const sim::Door& d : world.doors) {
    if (d.IsClosed(t_s)) out.push_back(d.segment);
  }
  for (const sim::Box& b : world.boxes) {
    const std::vector<Segment> outline = OutlineOf(BoxAt(b, t_s));
    out.insert(out.end(), outline.begin(), outline.end());
  }
  return out;
}

std::vector<Segment> GoneSurfaces(const sim::World& world, double end_s) {
  std::vector<Segment> out;
  for (const sim::Door& d : world.doors) {
    const bool closed_once =
        std::any_of(d.closed_intervals_s.begin(), d.closed_intervals_s.end(),
                    [end_s](const auto& iv) { return iv.first <= end_s && iv.second > 0.0; });
    if (closed_once && !d.IsClosed(end_s)) out.push_back(d.segment);
  }
  for (const sim::Box& b : world.boxes) {
    const sim::Box last = BoxAt(b, end_s);
    std::vector<sim::Box> poses{b};
    for (const sim::BoxMove& m : b.moves) {
      if (m.t_s <= end_s) poses.push_back(BoxAt(b, m.t_s));
    }
    for (const sim::Box& pose : poses) {
      if (SamePose(pose, last)) continue;
      const std::vector<Segment> outline = OutlineOf(pose);
      out.insert(out.end(), outline.begin(), outline.end());
    }
  }
  return out;
}

GroundTruth TruthOf(const sim::World& world, double end_s) {
  return {TrueWalls(world, end_s), WallsAt(world, end_s), GoneSurfaces(world, end_s),
          std::make_shared<const sim::World>(world), end_s};
}

void WriteTruthWalls(const std::string& prefix, const GroundTruth& truth) {
  io::WriteSegments(prefix + "walls.tsv", truth.walls);
  if (truth.gone.empty()) return;
  io::WriteSegments(prefix + "walls_now.tsv", truth.walls_now);
  io::WriteSegments(prefix + "gone.tsv", truth.gone);
}

std::optional<GroundTruth> ReadTruthWalls(const std::string& prefix) {
  if (!std::filesystem::exists(prefix + "walls.tsv")) return std::nullopt;
  GroundTruth truth;
  truth.walls = io::ReadSegments(prefix + "walls.tsv");
  if (std::filesystem::exists(prefix + "gone.tsv")) {
    truth.walls_now = io::ReadSegments(prefix + "walls_now.tsv");
    truth.gone = io::ReadSegments(prefix + "gone.tsv");
  }
  return truth;
}

}  // namespace lifelong::eval
