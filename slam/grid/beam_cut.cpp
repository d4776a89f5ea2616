// How two cuts of a beam combine (beam_cut.hpp).
#include "slam/grid/beam_cut.hpp"

#include <algorithm>
#include <cstddef>

namespace lifelong::slam {

BeamCut Merge(const BeamCut& a, const BeamCut& b) {
  BeamCut m{a.beam, std::min(a.free_to_m, b.free_to_m), 0.0f};
  if (a.Resumes() && b.Resumes()) m.resume_m = std::max(a.resume_m, b.resume_m);
  return m;
}

std::vector<BeamCut> MergeCuts(const std::vector<BeamCut>& a, const std::vector<BeamCut>& b) {
  std::vector<BeamCut> out;
  out.reserve(a.size() + b.size());
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].beam < b[j].beam)) {
      out.push_back(a[i++]);
    } else if (i == a.size() || b[j].beam < a[i].beam) {
      out.push_back(b[j++]);
    } else {
      out.push_back(Merge(a[i++], b[j++]));
    }
  }
  return out;
}

}  // namespace lifelong::slam
