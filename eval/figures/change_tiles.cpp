// The report's strip of changed objects (eval/figures/change_tiles.hpp).
#include "eval/figures/change_tiles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "eval/figures/draw.hpp"
#include "eval/figures/map_figure.hpp"

namespace lifelong::eval {
namespace {

constexpr double kMarginM = 1.0;    // map shown around the object
constexpr double kMPerPx = 0.0125;  // 4 px a 5 cm cell
constexpr int kGapPx = 6;           // white between tiles

Image Tile(const ObjectPresent& o, const OccupancyGrid& grid, const Pose2& T_truth_est) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const std::vector<Segment>* set : {&o.present, &o.past}) {
    for (const Segment& s : *set) {
      x0 = std::min({x0, s.x0, s.x1});
      y0 = std::min({y0, s.y0, s.y1});
      x1 = std::max({x1, s.x0, s.x1});
      y1 = std::max({y1, s.y0, s.y1});
    }
  }
  FigureLayers layers;
  layers.grid = &grid;
  layers.T_frame_grid = T_truth_est;
  layers.scale_bar = false;
  // Outlines as two-pose paths: the present in the truth's colour, the past in odometry's.
  for (const auto& [set, kind] : {std::pair{&o.past, TrajectoryKind::kOdometry},
                                  std::pair{&o.present, TrajectoryKind::kTrue}}) {
    for (const Segment& s : *set) {
      layers.trajectories.push_back({kind, {Pose2(s.x0, s.y0, 0.0), Pose2(s.x1, s.y1, 0.0)}});
    }
  }
  return RenderFigure(
      CanvasCovering(x0 - kMarginM, y0 - kMarginM, x1 + kMarginM, y1 + kMarginM, kMPerPx), layers);
}

}  // namespace

std::string WriteChangeTiles(const std::string& path, const ChangeRecall& change,
                             const OccupancyGrid& grid, const Pose2& T_truth_est) {
  std::vector<Image> tiles;
  std::string caption;
  for (const auto& [name, o] : change.objects) {
    if (o.present.empty() && o.past.empty()) continue;
    tiles.push_back(Tile(o, grid, T_truth_est));
    caption += (caption.empty() ? "" : "; ") + name + ": ";
    if (!o.shows_present) {
      caption += "not seen as it stands";
      continue;
    }
    char seen[48];
    std::snprintf(seen, sizeof seen, "seen %.0f s before the end", o.since_seen_s.value_or(0.0));
    caption += std::string(*o.shows_present ? "shown as it stands" : "not shown as it stands") +
               ", " + seen;
  }
  Image strip;
  for (const Image& t : tiles) {
    strip.width += t.width + (strip.width > 0 ? kGapPx : 0);
    strip.height = std::max(strip.height, t.height);
  }
  if (tiles.empty()) return "";
  strip.rgb.assign(static_cast<std::size_t>(strip.width) * strip.height * 3, 255);
  int left = 0;
  for (const Image& t : tiles) {
    for (int y = 0; y < t.height; ++y) {
      std::copy_n(t.rgb.begin() + static_cast<std::ptrdiff_t>(y) * t.width * 3, t.width * 3,
                  strip.rgb.begin() + (static_cast<std::ptrdiff_t>(y) * strip.width + left) * 3);
    }
    left += t.width + kGapPx;
  }
  WritePng(path, strip);
  return caption;
}

}  // namespace lifelong::eval
