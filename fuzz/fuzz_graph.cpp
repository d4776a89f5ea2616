// libFuzzer target: io::ParseGraph (g2o / TORO pose graphs) from an istringstream.
// lifelong::InputError is the expected answer to bad input.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "io/graph_file.hpp"
#include "sensor/input_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    lifelong::io::ParseGraph(in, "fuzz.g2o");
  } catch (const lifelong::InputError&) {
  }
  return 0;
}
