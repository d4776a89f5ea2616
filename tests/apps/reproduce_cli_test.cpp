// `lifelong reproduce` as a whole process: a small book over corridor_3 runs its sweep,
// judges its claims and writes the book; a second run resumes (nothing runs again); bad
// input exits 2 naming the file, line and field.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_lifelong.hpp"

namespace {

namespace fs = std::filesystem;
using lifelong::test::ExpectInputError;
using lifelong::test::Lifelong;
using lifelong::test::Read;
using lifelong::test::Result;
using lifelong::test::WriteFresh;
const std::string kSource = LIFELONG_SOURCE_DIR;

// A book of one experiment: corridor_3 over two seeds, standard and pruned.
fs::path Book(const std::string& claims) {
  WriteFresh("reproduce_", "spec.yaml",
             "scenarios: [" + kSource +
                 "/scenarios/corridor_3.yaml]\nseeds: [1, 2]\nmodes: [standard, pruned]\n");
  return WriteFresh("reproduce_", "book.yaml",
                    "experiments:\n"
                    "  - id: corridor\n"
                    "    title: the corridor\n"
                    "    quick: reproduce_spec.yaml\n"
                    "    claims:\n" +
                        claims);
}

TEST(ReproduceCli, WritesTheBookAndResumes) {
  const fs::path book = Book(
      "      - {claim: fewer nodes, figure: nodes_final, mode: pruned, expect: lower,\n"
      "         seed: constant, where: Fig. 6.1}\n"
      "      - {claim: share kept, figure: scans_kept_pct, mode: pruned, expect: report}\n");
  const fs::path out = lifelong::test::FreshPath("reproduce_", "out");
  const std::string args = "reproduce --book " + book.string() + " -o " + out.string() + " -j 2";
  const Result r = Lifelong(args);
  ASSERT_EQ(r.code, 0) << r.output;
  // Two seeds: an interval exists, and pruned's node count is far below standard's.
  EXPECT_NE(r.output.find("fewer nodes [corridor_3]: holds at 95 % (2 seeds)"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("share kept [corridor_3]: reported"), std::string::npos) << r.output;
  const std::string md = Read(out / "results.md");
  EXPECT_NE(md.find("| fewer nodes (nodes_final) | corridor_3 | constant (Fig. 6.1) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("profile quick"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "index.html"));
  EXPECT_TRUE(fs::exists(out / "reproduce_spec" / "runs.csv"));
  // A second run finds every cell up to date and writes the same verdicts.
  const Result again = Lifelong(args);
  ASSERT_EQ(again.code, 0) << again.output;
  EXPECT_NE(again.output.find("holds at 95 %"), std::string::npos) << again.output;
  EXPECT_EQ(Read(out / "results.md"), md);
}

TEST(ReproduceCli, BadInputExitsTwoNamingTheField) {
  const fs::path book =
      Book("      - {claim: fewer nodes, figure: nodes_final, mode: pruned-glc, expect: lower}\n");
  ExpectInputError(Lifelong("reproduce --book " + book.string() + " -o " +
                            lifelong::test::FreshPath("reproduce_", "bad").string()),
                   book.string() + ":6: field 'experiments[0].claims[0].mode'");
  const Result profile = Lifelong("reproduce --profile medium -o /tmp/x");
  EXPECT_EQ(profile.code, 2) << profile.output;
  const Result slurm_only = Lifelong("reproduce --partition p -o /tmp/x");
  EXPECT_EQ(slurm_only.code, 2) << slurm_only.output;
  EXPECT_NE(slurm_only.output.find("need --slurm"), std::string::npos) << slurm_only.output;
}

}  // namespace
