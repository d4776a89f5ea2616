// How two cuts of a beam combine (slam/grid/beam_cut.hpp).
#include "slam/grid/beam_cut.hpp"

#include <vector>

#include <gtest/gtest.h>

namespace lifelong::slam {
namespace {

TEST(BeamCut, TwoCutsOfABeamKeepWhatBothKeep) {
  const BeamCut gone{7, 6.0f, 0.0f};         // its return went: free up to it
  const BeamCut crossed{7, 3.7f, 5.3f};      // an object now stands across it at 4 m
  const BeamCut crossed_far{7, 4.5f, 6.1f};  // ...and another at 4.8 m
  EXPECT_EQ(Merge(gone, crossed), (BeamCut{7, 3.7f, 0.0f}));  // the return stays gone
  EXPECT_EQ(Merge(crossed, gone), (BeamCut{7, 3.7f, 0.0f}));
  EXPECT_EQ(Merge(crossed, crossed_far), (BeamCut{7, 3.7f, 6.1f}));
  EXPECT_EQ(Merge(crossed, crossed), crossed);
}

TEST(BeamCut, ListsMergeByBeam) {
  const std::vector<BeamCut> a{{1, 2.0f, 0.0f}, {4, 3.0f, 4.0f}, {9, 1.0f, 0.0f}};
  const std::vector<BeamCut> b{{0, 5.0f, 0.0f}, {4, 2.5f, 0.0f}, {12, 1.5f, 2.5f}};
  const std::vector<BeamCut> want{
      {0, 5.0f, 0.0f}, {1, 2.0f, 0.0f}, {4, 2.5f, 0.0f}, {9, 1.0f, 0.0f}, {12, 1.5f, 2.5f}};
  EXPECT_EQ(MergeCuts(a, b), want);
  EXPECT_EQ(MergeCuts(b, a), want);
  EXPECT_EQ(MergeCuts(a, {}), a);
  EXPECT_EQ(MergeCuts({}, b), b);
}

}  // namespace
}  // namespace lifelong::slam
