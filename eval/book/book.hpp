// `lifelong reproduce`: the seed's chapter 6 (Kretzschmar 2009) as a results book. A BOOK
// file (book/chapter6.yaml) lists experiments; each names a sweep SPEC per profile (quick:
// fewer seeds and shorter scenarios, for one machine; full: for a cluster) and the seed's
// claims it tests. Each experiment runs as a sweep (eval/sweep/sweep_run.hpp), so it resumes and
// runs on Slurm like any sweep; each claim is judged on the per-seed differences of one
// figure between two modes of the same cell (same world, route and noise):
//
//   experiments:
//     - id: corridor                              # [a-z0-9_-]+, unique
//       title: "§6.1 Many re-traversals of a corridor"
//       quick: quick/corridor.yaml                # SPECs, relative to the BOOK; one may be
//       full: full/corridor.yaml                  # absent (not in that profile)
//       claims:
//         - claim: pruned keeps fewer nodes
//           figure: nodes_final                   # a figure of summary.json (runs.csv column)
//           mode: pruned
//           baseline: standard                    # default: the SPEC's baseline
//           expect: lower                         # lower | higher | report (no verdict)
//           seed: "constant node count"           # the seed's value or statement
//           where: "Fig. 6.1"                     # the seed's figure or table
//       figures:                                  # a cell's figures shown as the seed's
//         - {file: nodes.png, seed: "Fig. 6.1"}   # (default: time_per_obs.png, nodes.png)
//       logs_optional: true    # its SPECs name public logs the project does not ship: a
//                              # missing one leaves the experiment "not run", saying where
//                              # it was looked for and where to get it (`get`)
//       get: "data/carmen/x-corrected.log.gz of github.com/..."
//
// Verdict per scenario or log: "holds" when the 95 % interval of the mean difference (mode −
// baseline) lies on the expected side of 0, "does not hold" when it lies on the other,
// "inconclusive" when it contains 0 or rests on fewer than two seeds.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "eval/sweep/sweep_collect.hpp"
#include "eval/sweep/sweep_stats.hpp"

namespace lifelong::eval {

enum class Expect { kLower, kHigher, kReport };

struct BookClaim {
  std::string claim, figure, mode, baseline, seed_value, seed_where;
  Expect expect = Expect::kLower;
  int line = 0;
};

/// A figure of one of the experiment's cells that stands beside one of the seed's: a file
/// relative to a cell's directory ("nodes.png", "pruned/map.png") and the seed's figure it
/// reads like.
struct BookFigure {
  std::string file, seed;
};

struct BookExperiment {
  std::string id, title;
  std::vector<BookFigure> figures;
  std::string quick_spec, full_spec;  ///< absolute; empty: not in that profile
  std::vector<BookClaim> claims;
  /// logs_optional: the logs each profile's SPEC names that are not here (absolute).
  std::vector<std::string> quick_missing, full_missing;
  std::string get;  ///< where to get them
};

struct Book {
  std::string file;
  std::vector<BookExperiment> experiments;
};

/// Reads and checks a BOOK: both profiles' SPECs load (LoadSweepSpec) and name every
/// claim's modes. Throws lifelong::InputError naming the file, line and field.
Book LoadBook(const std::string& path);

enum class Verdict { kHolds, kDoesNotHold, kInconclusive, kReported };
std::string VerdictText(Verdict v);

/// One claim on one scenario or log of its experiment's sweep.
struct ClaimResult {
  const BookClaim* claim = nullptr;
  std::string source;
  SampleStats baseline, mode, difference;  ///< difference: per seed, mode − baseline
  Verdict verdict = Verdict::kInconclusive;
};

/// The claim judged on every source of the tables (cells with both modes and the figure).
std::vector<ClaimResult> JudgeClaim(const BookClaim& claim, const SweepTables& tables);

/// An experiment's outcome: its sweep's tables (and where they are) and its claims judged.
struct ExperimentResult {
  const BookExperiment* experiment = nullptr;
  std::string dir;      ///< the sweep directory, relative to the book's; empty: not in the profile
  std::string not_run;  ///< why the experiment did not run (its logs are missing); empty: it ran
  SweepTables tables;
  std::vector<ClaimResult> claims;
  std::vector<std::string> charts;  ///< the sweep report's charts, relative to the book's dir
  /// The experiment's figures (BookFigure) of its first cell that has each, `file` relative
  /// to the book's dir.
  std::vector<BookFigure> figures;
};

struct BookOutcome {
  std::string profile;  ///< quick | full
  std::string commit;   ///< of the program that ran it
  std::string day;      ///< YYYY-MM-DD
  std::vector<ExperimentResult> experiments;
};

/// A scenario's or log's file name without its folder and .yaml: how the book names it.
std::string SourceName(const std::string& source);

/// DIR/results.md and DIR/index.html (each atomically).
void WriteBook(const BookOutcome& outcome, const std::string& dir);
/// The markdown of results.md.
std::string BookMarkdown(const BookOutcome& outcome);
/// A figure's caption: "As the seed's Fig. 6.7 (...)", or for a figure listed with seed
/// "– (what it shows)", one the seed has no counterpart of, "Not in the seed: what it shows".
std::string FigureCaption(const BookFigure& figure);

}  // namespace lifelong::eval
