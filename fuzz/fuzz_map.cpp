// libFuzzer target: io::ParseMapYaml and io::ParsePgmImage (ROS map_server YAML + P5 PGM)
// from one input split at the `@@PGM` line (fuzz/map_input.hpp). The image is parsed even
// when the YAML is rejected (with the default MapYaml), so both parsers see every input.
// lifelong::InputError is the expected answer to bad input; a grid that breaks its own
// invariants aborts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "fuzz/map_input.hpp"
#include "io/map_file.hpp"
#include "sensor/input_error.hpp"

namespace {

void Check(bool ok) {
  if (!ok) std::abort();
}

void CheckGrid(const lifelong::OccupancyGrid& g) {
  Check(g.width > 0 && g.height > 0);
  Check(g.p_occ.size() == static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height));
  Check(std::isfinite(g.resolution_m) && g.resolution_m > 0.0);
  Check(std::isfinite(g.origin_x_m) && std::isfinite(g.origin_y_m));
  for (float p : g.p_occ) Check(p == 0.0f || p == 1.0f || p == lifelong::OccupancyGrid::kUnknown);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const lifelong::fuzz::MapInput input =
      lifelong::fuzz::SplitMapInput(std::string(reinterpret_cast<const char*>(data), size));
  lifelong::io::MapYaml yaml;
  try {
    std::istringstream in(input.yaml);
    yaml = lifelong::io::ParseMapYaml(in, "fuzz.yaml");
    Check(!yaml.image.empty() && yaml.image_line > 0);
  } catch (const lifelong::InputError&) {
  }
  try {
    std::istringstream in(input.pgm);
    CheckGrid(lifelong::io::ParsePgmImage(in, "fuzz.pgm", yaml));
  } catch (const lifelong::InputError&) {
  }
  return 0;
}
