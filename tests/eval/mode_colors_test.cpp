// One colour per mode (eval/figures/mode_colors.hpp): fixed for the known modes, distinct, and a
// stable fallback for names it does not know.
#include "eval/figures/mode_colors.hpp"

#include <set>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

namespace lifelong::eval {
namespace {

std::tuple<int, int, int> Key(const render::Rgb& c) { return {c.r, c.g, c.b}; }

const char* const kNamed[] = {"standard",   "pruned",     "pruned-exact",   "pruned-naive",
                              "pruned-glc", "pruned-nfr", "pruned-overlap", "pruned-dpg"};

TEST(ModeColoursTest, KnownModesHaveDistinctFixedColours) {
  std::set<std::tuple<int, int, int>> seen;
  for (const char* m : kNamed) seen.insert(Key(ModeColour(m)));
  EXPECT_EQ(seen.size(), 8u);
  EXPECT_EQ(ModeColourHex("standard"), "#1f77b4");  // the seed's blue ...
  EXPECT_EQ(ModeColourHex("pruned"), "#d62728");    // ... and red
}

TEST(ModeColoursTest, UnknownModesGetAStableColourUnlikeTheKnownOnes) {
  EXPECT_EQ(ModeColourHex("pruned-something-new"), ModeColourHex("pruned-something-new"));
  std::set<std::string> known;
  for (const char* m : kNamed) known.insert(ModeColourHex(m));
  std::set<std::string> fallback;
  for (const char* m : {"a", "b", "c", "d", "e", "f", "g", "h", "x-1", "x-2", "y", "z"}) {
    const std::string hex = ModeColourHex(m);
    EXPECT_EQ(known.count(hex), 0u) << m;
    fallback.insert(hex);
  }
  EXPECT_GT(fallback.size(), 1u);  // not one colour for every unknown name
}

// Every policy with every sparsifier (issue #35's table): ten modes, ten colours; a pair
// with the seed's sparsifier is its named mode's colour.
TEST(ModeColoursTest, EachPolicyWithEachSparsifierHasItsOwnColour) {
  std::set<std::tuple<int, int, int>> seen;
  for (const char* m :
       {"standard", "pruned", "pruned-glc", "pruned-nfr", "pruned-dpg", "dpg+glc",
        "dpg+nfr-subgraph", "pruned-overlap", "overlap+glc", "overlap+nfr-subgraph"})
    seen.insert(Key(ModeColour(m)));
  EXPECT_EQ(seen.size(), 10u);
  EXPECT_EQ(ModeColourHex("dpg+chow-liu"), ModeColourHex("pruned-dpg"));
  EXPECT_EQ(ModeColourHex("information-gain+chow-liu"), ModeColourHex("pruned"));
  EXPECT_NE(ModeColourHex("dpg+glc"), ModeColourHex("dpg+nfr-subgraph"));
}

TEST(ModeColoursTest, HexIsLowerCaseRrggbb) { EXPECT_EQ(HexColour({255, 0, 16}), "#ff0010"); }

}  // namespace
}  // namespace lifelong::eval
