// A beam of a scan that no longer shows the world as far as it reaches (a removal policy's
// verdict, removal_policy_dpg.cpp), and how two verdicts on one beam combine.
#pragma once

#include <cstdint>
#include <vector>

namespace lifelong::slam {

/// A beam of a scan traced as free space up to free_to_m, without its return: the part of
/// a beam that still shows the world when its return (or its end) no longer does.
/// free_to_m <= 0 leaves the beam out. With resume_m > free_to_m the beam is traced again
/// from resume_m to its end, with its return: an object now stands across it, and what lay
/// beyond still does.
struct BeamCut {
  std::uint32_t beam = 0;
  float free_to_m = 0.0f;
  float resume_m = 0.0f;  ///< 0: the beam ends at free_to_m
  bool Resumes() const { return resume_m > free_to_m; }
  bool operator==(const BeamCut& o) const {
    return beam == o.beam && free_to_m == o.free_to_m && resume_m == o.resume_m;
  }
};

/// Two cuts of one beam as one: free up to the nearer end, and traced again only when both
/// resume, from the farther resume point (what one of them takes out stays out; a beam
/// whose return is gone does not get it back).
BeamCut Merge(const BeamCut& a, const BeamCut& b);

/// Two cut lists, each ascending by beam with a beam once, as one such list; a beam in both
/// is cut by Merge of its two cuts.
std::vector<BeamCut> MergeCuts(const std::vector<BeamCut>& a, const std::vector<BeamCut>& b);

}  // namespace lifelong::slam
