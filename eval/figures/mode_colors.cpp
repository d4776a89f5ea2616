#include "eval/figures/mode_colors.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

namespace lifelong::eval {
namespace {

// Known modes. Blue and red are the seed's "no graph reduction" and "our approach";
// the others avoid the edge colours of the maps (orange, magenta, teal) where they can.
constexpr std::array<std::pair<const char*, render::Rgb>, 8> kKnown = {{
    {"standard", {31, 119, 180}},         // blue
    {"pruned", {214, 39, 40}},            // red
    {"pruned-exact", {44, 160, 44}},      // green
    {"pruned-naive", {140, 86, 75}},      // brown
    {"pruned-glc", {148, 103, 189}},      // purple
    {"pruned-nfr", {188, 189, 34}},       // olive
    {"pruned-overlap", {227, 119, 194}},  // pink
    {"pruned-dpg", {23, 190, 207}},       // cyan
}};

// POLICY+SPARSIFIER: its policy's colour (that of its mode with the seed's Chow-Liu tree),
// darker or lighter by sparsifier, so a table of every pair reads by policy at a glance.
constexpr std::array<std::pair<const char*, const char*>, 3> kPolicyMode = {{
    {"information-gain", "pruned"},
    {"overlap", "pruned-overlap"},
    {"dpg", "pruned-dpg"},
}};
constexpr std::array<std::pair<const char*, double>, 7> kSparsifierShade = {{
    {"chow-liu", 0.0},
    {"glc", -0.45},  // toward black
    {"glc-dense", -0.25},
    {"nfr-subgraph", 0.45},  // toward white
    {"nfr-tree", 0.25},
    {"exact", -0.65},
    {"naive", 0.65},
}};

// Unknown modes: colours distinct from the known ones.
constexpr std::array<render::Rgb, 6> kFallback = {{
    {127, 127, 127},  // grey
    {255, 127, 14},   // orange
    {57, 59, 121},    // navy
    {0, 0, 0},        // black
    {255, 187, 0},    // gold
    {0, 100, 60},     // dark green
}};

std::optional<render::Rgb> KnownColour(const std::string& mode) {
  for (const auto& [name, colour] : kKnown) {
    if (mode == name) return colour;
  }
  return std::nullopt;
}

/// c moved toward white (shade > 0) or black (shade < 0) by |shade|.
render::Rgb Shaded(const render::Rgb& c, double shade) {
  const auto move = [&](std::uint8_t v) {
    const double target = shade > 0.0 ? 255.0 : 0.0;
    return static_cast<std::uint8_t>(v + (target - v) * std::abs(shade) + 0.5);
  };
  return {move(c.r), move(c.g), move(c.b)};
}

std::optional<render::Rgb> PairColour(const std::string& mode) {
  const std::size_t plus = mode.find('+');
  if (plus == std::string::npos) return std::nullopt;
  const std::string policy = mode.substr(0, plus), sparsifier = mode.substr(plus + 1);
  for (const auto& [p, named] : kPolicyMode) {
    if (policy != p) continue;
    for (const auto& [sp, shade] : kSparsifierShade) {
      if (sparsifier == sp) return Shaded(*KnownColour(named), shade);
    }
  }
  return std::nullopt;
}

std::uint32_t Fnv1a(const std::string& s) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : s) h = (h ^ c) * 16777619u;
  return h;
}

}  // namespace

render::Rgb ModeColour(const std::string& mode) {
  if (const auto known = KnownColour(mode)) return *known;
  if (const auto pair = PairColour(mode)) return *pair;
  return kFallback[Fnv1a(mode) % kFallback.size()];
}

std::string HexColour(const render::Rgb& c) {
  char buf[8];
  std::snprintf(buf, sizeof(buf), "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

std::string ModeColourHex(const std::string& mode) { return HexColour(ModeColour(mode)); }

}  // namespace lifelong::eval
