// libFuzzer target: io::ParseRelations (Kümmerle et al. 2009 relations files) from an
// istringstream, with the Intel time offset. lifelong::InputError is the expected answer to
// bad input; a relation with a non-finite number or an unnormalized angle aborts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "io/relations.hpp"
#include "sensor/input_error.hpp"

constexpr double kPi = 3.14159265358979323846;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const auto relations = lifelong::io::ParseRelations(in, "fuzz.relations",
                                                        lifelong::io::kIntelRelationsTimeOffsetS);
    for (const lifelong::Relation& r : relations) {
      const lifelong::Pose2& T = r.T_1_2;
      if (!std::isfinite(r.t1_s) || !std::isfinite(r.t2_s) || !std::isfinite(T.x) ||
          !std::isfinite(T.y) || !(std::abs(T.theta) <= kPi)) {
        std::abort();
      }
    }
  } catch (const lifelong::InputError&) {
  }
  return 0;
}
