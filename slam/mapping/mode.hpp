// The mapper's modes: a mode is a removal policy (removal_policy.hpp: which node goes) and a
// sparsifier (sparsifier.hpp: what replaces its elimination clique), and nothing else
// (DESIGN.md "Methods as parts"). The standard approach has neither and never removes a node.
// The named modes are rows of one table (mode.cpp); any other pair is the mode named
// POLICY+SPARSIFIER, so a mode's name always says what it runs.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace lifelong::slam {

struct Mode {
  std::string name = "standard";
  std::string policy;      ///< a RemovalPolicyNames() entry; empty: never removes (standard)
  std::string sparsifier;  ///< a SparsifierNames() entry; empty exactly when policy is
  bool Prunes() const { return !policy.empty(); }
};

/// The named modes, in the order help and errors list them: standard, pruned, pruned-exact,
/// pruned-naive, pruned-glc, pruned-nfr, pruned-overlap, pruned-dpg.
const std::vector<Mode>& NamedModes();

/// The named mode `name`; std::invalid_argument when there is none (for code and tests that
/// name a mode of the table).
Mode NamedMode(const std::string& name);

/// A named mode, or POLICY+SPARSIFIER (for example node-budget+glc); nullopt when neither.
std::optional<Mode> ParseMode(const std::string& name);

/// The named modes' names joined by ", ", and the POLICY+SPARSIFIER form with the known
/// policies and sparsifiers, for errors and help.
std::string ModeList();

}  // namespace lifelong::slam
