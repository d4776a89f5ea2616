// libFuzzer target: io::ParseTum (TUM RGB-D trajectories) from an istringstream.
// lifelong::InputError is the expected answer to bad input; a pose with a non-finite number
// or an unnormalized angle aborts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "io/tum.hpp"
#include "sensor/input_error.hpp"

constexpr double kPi = 3.14159265358979323846;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    for (const lifelong::StampedPose& p : lifelong::io::ParseTum(in, "fuzz.tum")) {
      const lifelong::Pose2& T = p.T_world_robot;
      if (!std::isfinite(p.stamp_s) || !std::isfinite(T.x) || !std::isfinite(T.y) ||
          !(std::abs(T.theta) <= kPi)) {
        std::abort();
      }
    }
  } catch (const lifelong::InputError&) {
  }
  return 0;
}
