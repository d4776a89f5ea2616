// The entropy of one cell of the counting grid (seed eqs. 3.10, 5.10): p = hits / (hits +
// misses), H = -p log2 p - (1 - p) log2 (1 - p); an unknown cell has 1 bit.
#include <array>
#include <cmath>
#include <cstdint>

#include "slam/grid/grid_map.hpp"

namespace lifelong::slam {
namespace {

// k log2 k for the small counts that make up almost every cell.
constexpr std::uint64_t kTableSize = 4096;

double XLog2X(std::uint64_t k) {
  static const std::array<double, kTableSize> table = [] {
    std::array<double, kTableSize> t{};
    for (std::uint64_t i = 1; i < kTableSize; ++i) {
      t[i] = static_cast<double>(i) * std::log2(static_cast<double>(i));
    }
    return t;
  }();
  return k < kTableSize ? table[k] : static_cast<double>(k) * std::log2(static_cast<double>(k));
}

}  // namespace

double CellEntropyBits(CellCounts counts) {
  if (counts.hits == 0 || counts.misses == 0) return counts.hits == counts.misses ? 1.0 : 0.0;
  const double n = static_cast<double>(counts.hits) + static_cast<double>(counts.misses);
  const double p = static_cast<double>(counts.hits) / n;
  return -p * std::log2(p) - (1.0 - p) * std::log2(1.0 - p);
}

std::int64_t QuantizedEntropyOf(CellCounts counts) {
  constexpr double kQuantaPerBit = 1.0 / kEntropyQuantumBits;
  if (counts.hits == 0 || counts.misses == 0) {
    return counts.hits == counts.misses ? static_cast<std::int64_t>(kQuantaPerBit) : 0;
  }
  // H = log2 n - (h log2 h + m log2 m) / n = (n log2 n - h log2 h - m log2 m) / n.
  const std::uint64_t n = std::uint64_t{counts.hits} + counts.misses;
  const double h = XLog2X(n) - XLog2X(counts.hits) - XLog2X(counts.misses);
  return std::llround(h / static_cast<double>(n) * kQuantaPerBit);
}

const std::array<std::int64_t, 64 * 64> kSmallCountsQuantizedEntropy = [] {
  std::array<std::int64_t, 64 * 64> table{};
  for (std::uint32_t h = 0; h < 64; ++h) {
    for (std::uint32_t m = 0; m < 64; ++m) table[h * 64 + m] = QuantizedEntropyOf({h, m});
  }
  return table;
}();

}  // namespace lifelong::slam
