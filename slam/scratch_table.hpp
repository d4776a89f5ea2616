// Sizing of the scratch tables that the matcher and the grid map rebuild for every scan.
// Internal to slam.
#pragma once

#include <cstddef>
#include <vector>

namespace lifelong::slam {

/// Resizes a table that is rebuilt many times at sizes varying by tens of percent, keeping
/// its memory (fresh multi-megabyte tables cost page faults). When it must grow, its
/// capacity becomes the new size plus an eighth, not the doubling std::vector::resize may
/// choose: memory past the largest table would only be dead weight. Contents are not kept
/// across a growth: the elements are then value-initialized, and the call returns true.
template <typename T>
bool ResizeTable(std::vector<T>* table, std::size_t size) {
  const bool grow = size > table->capacity();
  if (grow) {
    std::vector<T> fresh;
    fresh.reserve(size + size / 8);
    table->swap(fresh);
  }
  table->resize(size);
  return grow;
}

}  // namespace lifelong::slam
