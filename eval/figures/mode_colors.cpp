#include "eval/figures/mode_colors.hpp"

#include <array>
#include <cstdint>
#include <cstdio>
#include <utility>

namespace lifelong::eval {
namespace {

// Known modes. Blue and red are the seed's "no graph reduction" and "our approach";
// the others avoid the edge colours of the maps (orange, magenta, teal) where they can.
constexpr std::array<std::pair<const char*, render::Rgb>, 6> kKnown = {{
    {"standard", {31, 119, 180}},     // blue
    {"pruned", {214, 39, 40}},        // red
    {"pruned-exact", {44, 160, 44}},  // green
    {"pruned-naive", {140, 86, 75}},  // brown
    {"pruned-glc", {148, 103, 189}},  // purple
    {"pruned-nfr", {188, 189, 34}},   // olive
}};

// Unknown modes: colours distinct from the known ones.
constexpr std::array<render::Rgb, 6> kFallback = {{
    {227, 119, 194},  // pink
    {127, 127, 127},  // grey
    {23, 190, 207},   // cyan
    {255, 127, 14},   // orange
    {57, 59, 121},    // navy
    {0, 0, 0},        // black
}};

std::uint32_t Fnv1a(const std::string& s) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : s) h = (h ^ c) * 16777619u;
  return h;
}

}  // namespace

render::Rgb ModeColour(const std::string& mode) {
  for (const auto& [name, colour] : kKnown) {
    if (mode == name) return colour;
  }
  return kFallback[Fnv1a(mode) % kFallback.size()];
}

std::string HexColour(const render::Rgb& c) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

std::string ModeColourHex(const std::string& mode) { return HexColour(ModeColour(mode)); }

}  // namespace lifelong::eval
