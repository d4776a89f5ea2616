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
/// across a growth (elements are value-initialized then).
template <typename T>
void ResizeTable(std::vector<T>* table, std::size_t size) {
  if (size > table->capacity()) {
    std::vector<T> fresh;
    fresh.reserve(size + size / 8);
    table->swap(fresh);
  }
  table->resize(size);
}

}  // namespace lifelong::slam
