#include "eval/truth/world_state.hpp"

#include <algorithm>
#include <cstddef>

#include <filesystem>
#include <memory>

#include "io/segments_file.hpp"

namespace lifelong::eval {
std::vector<Segment> BoxOutlineAt(const sim::Box& box, double t_s) {
  sim::World one;
  one.boxes.push_back(box);
  for (const sim::BoxMove& m : box.moves) {
    if (m.t_s > t_s) break;
    one.boxes[0].center = m.center;
    one.boxes[0].yaw_rad = m.yaw_rad;
  }
  return sim::BoxSegments(one);
}

std::vector<Segment> PastBoxOutlines(const sim::Box& box, double end_s) {
  const auto same = [](const std::vector<Segment>& a, const std::vector<Segment>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const Segment& p, const Segment& q) {
                        return p.x0 == q.x0 && p.y0 == q.y0 && p.x1 == q.x1 && p.y1 == q.y1;
                      });
  };
  const std::vector<Segment> last = BoxOutlineAt(box, end_s);
  std::vector<double> times{0.0};
  for (const sim::BoxMove& m : box.moves) {
    if (m.t_s <= end_s) times.push_back(m.t_s);
  }
  std::vector<Segment> out;
  for (double t : times) {
    const std::vector<Segment> outline = BoxOutlineAt(box, t);
    if (!same(outline, last)) out.insert(out.end(), outline.begin(), outline.end());
  }
  return out;
}

std::vector<Segment> WallsAt(const sim::World& world, double t_s) {
  std::vector<Segment> out = sim::WallSegments(world);
  for (const sim::Door& d : world.doors) {
    if (d.IsClosed(t_s)) out.push_back(d.segment);
  }
  for (const sim::Box& b : world.boxes) {
    const std::vector<Segment> outline = BoxOutlineAt(b, t_s);
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
    const std::vector<Segment> past = PastBoxOutlines(b, end_s);
    out.insert(out.end(), past.begin(), past.end());
  }
  return out;
}

GroundTruth TruthOf(const sim::World& world, double end_s) {
  return {TrueWalls(world, end_s),
          WallsAt(world, end_s),
          GoneSurfaces(world, end_s),
          std::make_shared<const sim::World>(world),
          end_s,
          nullptr};
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

namespace {

/// True when the door is closed at some time in [0, end_s].
bool ClosedDuring(const sim::Door& door, double end_s) {
  return std::any_of(door.closed_intervals_s.begin(), door.closed_intervals_s.end(),
                     [end_s](const auto& iv) { return iv.first <= end_s && iv.second > 0.0; });
}

}  // namespace

std::vector<Segment> TrueWalls(const sim::World& world, double end_s) {
  std::vector<Segment> out = sim::WallSegments(world);
  for (const sim::Door& d : world.doors) {
    if (!ClosedDuring(d, end_s)) continue;  // open all run long: never a wall to see
    out.push_back(d.segment);
  }
  // Boxes at every pose they take during the run: a map may show any of them.
  sim::World moved = world;
  for (std::size_t step = 0;; ++step) {
    const std::vector<Segment> boxes = sim::BoxSegments(moved);
    out.insert(out.end(), boxes.begin(), boxes.end());
    bool any = false;
    for (std::size_t b = 0; b < world.boxes.size(); ++b) {
      if (step < world.boxes[b].moves.size() && world.boxes[b].moves[step].t_s <= end_s) {
        moved.boxes[b].center = world.boxes[b].moves[step].center;
        moved.boxes[b].yaw_rad = world.boxes[b].moves[step].yaw_rad;
        any = true;
      }
    }
    if (!any) break;
  }
  return out;
}

}  // namespace lifelong::eval
