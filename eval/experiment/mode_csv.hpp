// The per-mode CSVs of the output directory beside timeline.csv: marginalizations.csv,
// sparsifications.csv and loop_attempts.csv (docs/output-contract.md).
#pragma once

#include <string>
#include <vector>

#include "slam/mapping/mapper.hpp"

namespace lifelong::eval {

/// DIR/<mode>/marginalizations.csv: one row per removed node.
void WriteMarginalizations(const std::string& path, const slam::Mapper& mapper);
/// DIR/<mode>/sparsifications.csv: one row per edge-budget sparsification.
void WriteSparsifications(const std::string& path, const slam::Mapper& mapper);

/// One loop search and the observation it ran at.
struct LoopAttemptRow {
  int obs = 0;
  slam::LoopAttempt attempt;
};
/// DIR/<mode>/loop_attempts.csv: one row per loop search that had candidates.
void WriteLoopAttempts(const std::string& path, const std::vector<LoopAttemptRow>& rows);

}  // namespace lifelong::eval
