#include <cstring>
#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "eval/common/resources.hpp"

namespace lifelong::eval {
namespace {

// After a large block is freed, resetting the high-water mark brings the peak back down, so
// a later mode's peak does not include an earlier mode's memory.
TEST(ResourcesReset, PeakForgetsFreedMemory) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer keeps freed memory in quarantine";
#endif
  constexpr std::size_t kBytes = 256u << 20;
  {
    auto block = std::make_unique<char[]>(kBytes);
    std::memset(block.get(), 1, kBytes);  // touch every page
    ASSERT_TRUE(PeakRssMb().has_value());
    EXPECT_GT(*PeakRssMb(), 250.0);
  }
  if (!ResetPeakRss()) GTEST_SKIP() << "/proc/self/clear_refs is not writable here";
  EXPECT_LT(*PeakRssMb(), 200.0);
}

// The resident size read per observation (from /proc/self/statm) is the VmRSS line of
// /proc/self/status, and follows a block as it is touched.
TEST(ResourcesCurrent, ResidentSizeIsTheStatusFilesVmRss) {
  const auto vm_rss_mb = [] {
    std::ifstream in("/proc/self/status");
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
    }
    return -1.0;
  };
  const double before = vm_rss_mb();
  ASSERT_GT(before, 0.0) << "no VmRSS in /proc/self/status";
  const auto now = CurrentRssMb();
  ASSERT_TRUE(now.has_value());
  EXPECT_NEAR(*now, before, 0.5);  // a page or two may come or go between the reads
  constexpr std::size_t kBytes = 64u << 20;
  auto block = std::make_unique<char[]>(kBytes);
  std::memset(block.get(), 1, kBytes);
  EXPECT_GT(*CurrentRssMb(), *now + 60.0);
  EXPECT_NEAR(*CurrentRssMb(), vm_rss_mb(), 0.5);
}

}  // namespace
}  // namespace lifelong::eval
