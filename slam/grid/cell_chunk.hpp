// The 32 x 32-cell chunks that the counting grid stores its cells in, and that the gain
// index groups a scan's cells by: one layout for both (internal to slam).
#pragma once

#include <cstdint>

#include "slam/grid/grid_map.hpp"

namespace lifelong::slam::chunk {

constexpr int kBits = 5;  ///< 2^5 x 2^5 cells per chunk
constexpr int kSide = 1 << kBits;
constexpr int kMask = kSide - 1;

/// Floor division of a cell index by the chunk side (arithmetic shift, as GCC and Clang
/// define it).
inline int Of(int cell) { return cell >> kBits; }

/// One key for the chunk at (chunk_x, chunk_y).
inline std::uint64_t Key(int chunk_x, int chunk_y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(chunk_x)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(chunk_y));
}

/// The chunk coordinates a key was made of.
inline int XOf(std::uint64_t key) {
  return static_cast<int>(static_cast<std::uint32_t>(key >> 32));
}
inline int YOf(std::uint64_t key) { return static_cast<int>(static_cast<std::uint32_t>(key)); }

/// The first and last cells of the chunk a key was made of.
inline CellIndex FirstCell(std::uint64_t key) { return {XOf(key) * kSide, YOf(key) * kSide}; }
inline CellIndex LastCell(std::uint64_t key) {
  return {XOf(key) * kSide + kMask, YOf(key) * kSide + kMask};
}

/// The place of a cell within its chunk, row-major: (y mod 32) * 32 + x mod 32.
inline int Offset(CellIndex c) { return ((c.y & kMask) << kBits) | (c.x & kMask); }

}  // namespace lifelong::slam::chunk
