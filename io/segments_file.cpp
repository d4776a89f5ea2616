#include "io/segments_file.hpp"

#include "io/atomic_file.hpp"
#include "io/text_fields.hpp"

namespace lifelong::io {

void WriteSegments(const std::string& path, const std::vector<Segment>& segments) {
  std::string text = "# x0 y0 x1 y1 (m, world frame)\n";
  for (const Segment& s : segments) {
    std::string line;
    AppendFixed(&line, s.x0, 9);
    AppendFixed(&line, s.y0, 9);
    AppendFixed(&line, s.x1, 9);
    AppendFixed(&line, s.y1, 9);
    text += line + "\n";
  }
  WriteFileAtomically(path, text);
}

std::vector<Segment> ReadSegments(const std::string& path) {
  std::vector<Segment> out;
  ForEachNumericRow(path, {"x0", "y0", "x1", "y1"}, [&](int, const std::vector<double>& v) {
    out.push_back({v[0], v[1], v[2], v[3]});
  });
  return out;
}

}  // namespace lifelong::io
