// The per-mode CSVs of the output directory beside timeline.csv: marginalizations.csv,
// sparsifications.csv and loops.csv (docs/output-contract.md).
#pragma once

#include <string>

#include "slam/mapping/mapper.hpp"

namespace lifelong::eval {

/// DIR/<mode>/marginalizations.csv: one row per removed node.
void WriteMarginalizations(const std::string& path, const slam::Mapper& mapper);
/// DIR/<mode>/sparsifications.csv: one row per edge-budget sparsification.
void WriteSparsifications(const std::string& path, const slam::Mapper& mapper);

}  // namespace lifelong::eval
