// libFuzzer target: sim::LoadScenarioFromString on arbitrary text, with the world path
// resolved against the repository's scenarios/ folder (so `world: ../worlds/corridor.yaml`
// loads a shipped world). lifelong::InputError is the expected answer to bad input.
#include <cstddef>
#include <cstdint>
#include <string>

#include "sensor/input_error.hpp"
#include "sim/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    lifelong::sim::LoadScenarioFromString(text, "fuzz_scenario.yaml",
                                          LIFELONG_SOURCE_DIR "/scenarios");
  } catch (const lifelong::InputError&) {
  }
  return 0;
}
