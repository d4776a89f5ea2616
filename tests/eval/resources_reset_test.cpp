#include <cstring>
#include <memory>

#include <gtest/gtest.h>

#include "eval/resources.hpp"

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

}  // namespace
}  // namespace lifelong::eval
