// Relations reader (Kümmerle et al. 2009); see relations.hpp.
#include "io/relations.hpp"

#include <fstream>

#include "io/text_fields.hpp"
#include "sensor/input_bounds.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {

std::vector<Relation> ReadRelations(const std::string& path, double time_offset_s) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open file");
  return ParseRelations(in, path, time_offset_s);
}

std::vector<Relation> ParseRelations(std::istream& in, const std::string& name,
                                     double time_offset_s) {
  std::vector<Relation> relations;
  ForEachNumericRow(
      in, name, {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"},
      [&](int, const std::vector<double>& v) {
        relations.push_back({v[0] - time_offset_s, v[1] - time_offset_s, Pose2(v[2], v[3], v[7])});
      },
      {kMaxStampS, kMaxStampS, kMaxCoordinateM, kMaxCoordinateM, kMaxCoordinateM});
  return relations;
}

}  // namespace lifelong::io
