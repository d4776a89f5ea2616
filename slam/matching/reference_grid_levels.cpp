// The correlative matcher's coarse levels (Olson 2009, §III-B), built tile by tile where a
// search reads them; see ReferenceGrid::PrepareBounds in scan_matcher.hpp.
//
// Level l holds, at cell (x, y), the max of level 0 over [x, x + 2^l)^2: the max of level
// l - 1 at (x, y), (x + h, y), (x, y + h) and (x + h, y + h), h = 2^(l - 1), cells past the
// table's edge counting 0. With tiles of coarse_factor cells a side, h is at most half a tile,
// so level l on a tile reads level l - 1 on that tile and on its neighbours to the right, above
// and above right.
#include <algorithm>
#include <cstddef>

#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {

namespace {

// floor(a / b) for b > 0.
int FloorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

}  // namespace

void ReferenceGrid::ResetLevels() {
  num_levels_ = 1;
  while ((1 << (num_levels_ - 1)) < coarse_factor_) ++num_levels_;
  tile_ = coarse_factor_;
  tiles_x_ = width_ > 0 ? (width_ + tile_ - 1) / tile_ : 0;
  tiles_y_ = height_ > 0 ? (height_ + tile_ - 1) / tile_ : 0;
  const std::size_t cells = levels_[0].size();
  while (levels_.size() < static_cast<std::size_t>(num_levels_)) levels_.emplace_back();
  for (int l = 1; l < num_levels_; ++l) ResizeTable(&levels_[static_cast<std::size_t>(l)], cells);
  const auto tiles = static_cast<std::size_t>(tiles_x_) * static_cast<std::size_t>(tiles_y_);
  tile_ready_.assign(tiles, 0u);
}

void ReferenceGrid::PrepareBounds(const std::vector<std::vector<Eigen::Vector2i>>& cells, int reach,
                                  int top_level) const {
  top_level = std::min(top_level, num_levels_ - 1);
  if (top_level < 1 || tiles_x_ == 0 || tiles_y_ == 0) return;
  // The tile of every query cell, clamped into the table: a cell outside reads only tiles
  // within reach of the edge nearest it.
  std::vector<std::uint8_t> seed(tile_ready_.size(), 0);
  for (const auto& rotated : cells) {
    for (const Eigen::Vector2i& c : rotated) {
      const int tx = std::clamp(FloorDiv(c.x(), tile_), 0, tiles_x_ - 1);
      const int ty = std::clamp(FloorDiv(c.y(), tile_), 0, tiles_y_ - 1);
      seed[static_cast<std::size_t>(ty * tiles_x_ + tx)] = 1;
    }
  }
  // Grown by the reach (c + i lies at most ceil(reach / tile) tiles from c's), separably.
  const int d = (std::max(reach, 0) + tile_ - 1) / tile_;
  std::vector<std::uint8_t> across(seed.size(), 0);
  for (int ty = 0; ty < tiles_y_; ++ty) {
    for (int tx = 0; tx < tiles_x_; ++tx) {
      if (!seed[static_cast<std::size_t>(ty * tiles_x_ + tx)]) continue;
      for (int x = std::max(tx - d, 0); x <= std::min(tx + d, tiles_x_ - 1); ++x)
        across[static_cast<std::size_t>(ty * tiles_x_ + x)] = 1;
    }
  }
  const std::uint32_t top_bit = 1u << top_level;
  std::vector<std::uint32_t> need(seed.size(), 0u);
  for (int ty = 0; ty < tiles_y_; ++ty) {
    for (int tx = 0; tx < tiles_x_; ++tx) {
      if (!across[static_cast<std::size_t>(ty * tiles_x_ + tx)]) continue;
      for (int y = std::max(ty - d, 0); y <= std::min(ty + d, tiles_y_ - 1); ++y)
        need[static_cast<std::size_t>(y * tiles_x_ + tx)] = top_bit;
    }
  }
  // What each wanted tile of level l reads of level l - 1 (level 0 is built everywhere). A
  // tile wants itself, so the tiles of the top level get every level below (Descend reads
  // them at the same cells).
  for (int l = top_level; l >= 2; --l) {
    const std::uint32_t bit = 1u << l, below = 1u << (l - 1);
    for (int ty = 0; ty < tiles_y_; ++ty) {
      for (int tx = 0; tx < tiles_x_; ++tx) {
        if (!(need[static_cast<std::size_t>(ty * tiles_x_ + tx)] & bit)) continue;
        for (int y = ty; y <= std::min(ty + 1, tiles_y_ - 1); ++y) {
          for (int x = tx; x <= std::min(tx + 1, tiles_x_ - 1); ++x)
            need[static_cast<std::size_t>(y * tiles_x_ + x)] |= below;
        }
      }
    }
  }
  for (int l = 1; l <= top_level; ++l) BuildTiles(l, need);
}

void ReferenceGrid::PrepareAllBounds() const {
  if (num_levels_ < 2) return;
  const std::vector<std::uint32_t> need(tile_ready_.size(), (1u << num_levels_) - 2u);
  for (int l = 1; l < num_levels_; ++l) BuildTiles(l, need);
}

void ReferenceGrid::BuildTiles(int level, const std::vector<std::uint32_t>& need) const {
  const std::uint32_t bit = 1u << level;
  for (int ty = 0; ty < tiles_y_; ++ty) {
    for (int tx = 0; tx < tiles_x_; ++tx) {
      const auto t = static_cast<std::size_t>(ty * tiles_x_ + tx);
      if (!(need[t] & bit) || (tile_ready_[t] & bit)) continue;
      BuildTile(level, tx, ty);
      tile_ready_[t] |= bit;
    }
  }
}

void ReferenceGrid::BuildTile(int level, int tx, int ty) const {
  const Table& prev = levels_[static_cast<std::size_t>(level - 1)];
  Table& next = levels_[static_cast<std::size_t>(level)];
  const int h = 1 << (level - 1);
  const auto w = static_cast<std::size_t>(width_);
  const int x0 = tx * tile_, x1 = std::min(x0 + tile_, width_);
  // Columns whose right neighbour h on lies inside the table, then the rest (edge: 0).
  const int inner = std::max(x0, std::min(x1, width_ - h));
  for (int y = ty * tile_; y < std::min((ty + 1) * tile_, height_); ++y) {
    const float* a = prev.data() + static_cast<std::size_t>(y) * w;
    const float* b = y + h < height_ ? a + static_cast<std::size_t>(h) * w : nullptr;
    float* out = next.data() + static_cast<std::size_t>(y) * w;
    if (b != nullptr) {
      for (int x = x0; x < inner; ++x)
        out[x] = std::max(std::max(a[x], a[x + h]), std::max(b[x], b[x + h]));
      for (int x = inner; x < x1; ++x) out[x] = std::max(a[x], b[x]);
    } else {
      for (int x = x0; x < inner; ++x) out[x] = std::max(a[x], a[x + h]);
      for (int x = inner; x < x1; ++x) out[x] = a[x];
    }
  }
}

}  // namespace lifelong::slam
