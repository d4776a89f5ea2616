// Which clock a relations file uses. Kümmerle et al.'s relations carry absolute stamps
// while a log may count from its start (Intel's raw log: relation time = log time +
// 976052857.337284 s). The offset is found as the one that puts the most relation stamps
// on scan stamps.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "io/relations.hpp"

namespace lifelong::io {

/// s; a relation stamp and a scan stamp within this are the same instant.
constexpr double kRelationStampToleranceS = 1e-3;

/// How many relations have both stamps on a scan stamp (within tolerance_s) once
/// `offset_s` is subtracted from them. `sorted_scan_stamps` ascending.
std::size_t CountMatchedRelations(const std::vector<Relation>& relations,
                                  const std::vector<double>& sorted_scan_stamps, double offset_s,
                                  double tolerance_s = kRelationStampToleranceS);

/// How many relations have both stamps, once `offset_s` is subtracted, within
/// [first_s, last_s] (the log's time span): those that should land on scans.
std::size_t CountRelationsInside(const std::vector<Relation>& relations, double first_s,
                                 double last_s, double offset_s);

struct OffsetDetection {
  double offset_s = 0.0;    ///< s; relation time = log time + offset_s
  std::size_t matched = 0;  ///< relations with both stamps on scans at that offset
  /// Another offset fits as many relations (scans at a regular rate make every shift by
  /// whole periods fit): the clock cannot be told from the stamps.
  std::optional<double> also_fits_s;
};

/// The offset (relation time − log time) that puts the most relation stamps on scan stamps.
/// Candidates: 0, and each anchor relation stamp minus each scan stamp, for a few anchor
/// stamps spread over the file; each is scored on a spread sample of the relations and the
/// leaders are counted in full; the winner is then centred on the median gap between the
/// matched relation stamps and their scans. A file already in log time (offset 0 fits best) keeps
/// 0; otherwise a tie between offsets is reported in also_fits_s. matched == 0: none fits.
OffsetDetection DetectRelationsOffset(const std::vector<Relation>& relations,
                                      const std::vector<double>& sorted_scan_stamps,
                                      double tolerance_s = kRelationStampToleranceS);

/// The relations with `offset_s` subtracted from both stamps (file time to log time).
std::vector<Relation> ShiftRelations(std::vector<Relation> relations, double offset_s);

}  // namespace lifelong::io
