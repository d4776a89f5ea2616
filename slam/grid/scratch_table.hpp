// Sizing of the scratch tables that the matcher and the grid map rebuild for every scan.
// Internal to slam.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace lifelong::slam {

/// Resizes a table that is rebuilt many times at sizes varying by tens of percent, keeping
/// its memory (fresh multi-megabyte tables cost page faults). When it must grow, its
/// capacity at least doubles (and is at least the new size plus an eighth): growing by an
/// eighth at a time re-faulted the whole table at every step, 4 500 of an Intel run's 25 000
/// page faults. Capacity past the largest size used is never touched, so it is address
/// space, not resident memory. Contents are not kept across a growth: the elements are then
/// value-initialized (default-initialized with an UninitializedAllocator), and the call
/// returns true.
template <typename T, typename Allocator>
bool ResizeTable(std::vector<T, Allocator>* table, std::size_t size) {
  const bool grow = size > table->capacity();
  if (grow) {
    std::vector<T, Allocator> fresh;
    fresh.reserve(std::max(size + size / 8, 2 * table->capacity()));
    table->swap(fresh);
  }
  table->resize(size);
  return grow;
}

/// For tables whose every element is written before it is read: std::vector's resize then
/// leaves new trivial elements uninitialized instead of zeroing them first (a matcher's
/// coarse levels are rebuilt for every scan, at sizes that vary; zeroing them was 2-3 % of
/// a run).
template <typename T>
struct UninitializedAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}  // NOLINT: rebinding
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace lifelong::slam
