// libFuzzer target: sim::LoadWorldFromString on arbitrary text. lifelong::InputError is
// the expected answer to bad input; any other exception, crash, sanitizer report, hang
// or huge allocation is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "sensor/input_error.hpp"
#include "sim/world_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    lifelong::sim::LoadWorldFromString(text, "fuzz_world.yaml");
  } catch (const lifelong::InputError&) {
  }
  return 0;
}
