// Sizing of the scratch tables that the matcher and the grid map rebuild for every scan.
// Internal to slam.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace lifelong::slam {

/// Resizes a table that is rebuilt many times at sizes varying by tens of percent, keeping
/// its memory (fresh multi-megabyte tables cost page faults). When it must grow, its
/// capacity at least doubles (and is at least the new size plus an eighth): growing by an
/// eighth at a time re-faulted the whole table at every step, 4 500 of an Intel run's 25 000
/// page faults. Capacity past the largest size used is never touched, so it is address
/// space, not resident memory. Contents are not kept across a growth: the elements are then
/// value-initialized, and the call returns true.
template <typename T>
bool ResizeTable(std::vector<T>* table, std::size_t size) {
  const bool grow = size > table->capacity();
  if (grow) {
    std::vector<T> fresh;
    fresh.reserve(std::max(size + size / 8, 2 * table->capacity()));
    table->swap(fresh);
  }
  table->resize(size);
  return grow;
}

}  // namespace lifelong::slam
