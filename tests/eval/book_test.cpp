// The results book of `lifelong reproduce` (eval/book/book.hpp): a BOOK's bad input names its
// file, line and field; the shipped book loads in both profiles; a claim's verdict follows
// the 95 % interval of the per-seed differences; the markdown says the profile.
#include "eval/book/book.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "eval/sweep/sweep_spec.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

const std::string kSource = LIFELONG_SOURCE_DIR;

std::string Write(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(::testing::TempDir()) / "book_test";
  fs::create_directories(dir);
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

// A SPEC with standard and pruned on corridor_3.
std::string Spec() {
  return Write("spec.yaml", "scenarios: [" + kSource +
                                "/scenarios/corridor_3.yaml]\nseeds: [1, 2]\n"
                                "modes: [standard, pruned]\n");
}

std::string Experiment(const std::string& claim_extra, const std::string& experiment_extra = "") {
  Spec();
  return "experiments:\n"
         "  - id: corridor\n"
         "    title: the corridor\n"
         "    quick: spec.yaml\n" +
         experiment_extra +
         "    claims:\n"
         "      - claim: fewer nodes\n"
         "        figure: nodes_final\n"
         "        mode: pruned\n"
         "        expect: lower\n" +
         claim_extra;
}

void ExpectError(const std::string& text, int line, const std::string& field,
                 const std::string& words) {
  const std::string path = Write("book.yaml", text);
  try {
    LoadBook(path);
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(Book, BadInputNamesFileLineAndField) {
  ExpectError(Experiment("        colour: red\n"), 10, "experiments[0].claims[0].colour",
              "unknown");
  ExpectError(Experiment("        baseline: pruned-exact\n"), 10,
              "experiments[0].claims[0].baseline", "runs no mode pruned-exact");
  ExpectError(Experiment("").replace(Experiment("").find("lower"), 5, "smaller"), 9,
              "experiments[0].claims[0].expect", "lower, higher or report");
  ExpectError(Experiment("", "    full: missing.yaml\n"), 5, "experiments[0].full",
              "no such sweep SPEC");
  ExpectError(Experiment("").replace(Experiment("").find("id: corridor"), 12, "id: Corridor!"), 2,
              "experiments[0].id", "[a-z0-9_-]+");
  ExpectError("experiments: []\n", 1, "experiments", "non-empty");
  ExpectError(Experiment("", "    figures: [{file: ../../etc/x.png, seed: Fig. 6.1}]\n"), 5,
              "experiments[0].figures[0].file", "inside a cell's directory");
  ExpectError(Experiment("", "    figures: [{file: summary.json, seed: Fig. 6.1}]\n"), 5,
              "experiments[0].figures[0].file", "expected a .png");
  ExpectError(Experiment("", "    figures: [{file: nodes.png}]\n"), 5,
              "experiments[0].figures[0].seed", "");
}

// An experiment's figures: the seed's figure each stands for, as written; without any, the
// time per observation and nodes, which read like the seed's Fig. 6.1-6.4.
TEST(Book, AnExperimentNamesTheSeedsFigureEachOfItsFiguresStandsFor) {
  const Book given = LoadBook(Write(
      "book.yaml", Experiment("",
                              "    figures:\n"
                              "      - {file: pruned/map.png, seed: \"Fig. 6.7 (pruned)\"}\n")));
  ASSERT_EQ(given.experiments[0].figures.size(), 1u);
  EXPECT_EQ(given.experiments[0].figures[0].file, "pruned/map.png");
  EXPECT_EQ(given.experiments[0].figures[0].seed, "Fig. 6.7 (pruned)");
  const Book plain = LoadBook(Write("book.yaml", Experiment("")));
  ASSERT_EQ(plain.experiments[0].figures.size(), 2u);
  EXPECT_EQ(plain.experiments[0].figures[0].file, "time_per_obs.png");
  EXPECT_EQ(plain.experiments[0].figures[1].file, "nodes.png");
}

// A figure the seed has none of ("– (...)") is not captioned as the seed's.
TEST(Book, AFigureWithoutASeedCounterpartSaysSo) {
  EXPECT_EQ(FigureCaption({"pruned/map.png", "Fig. 6.7 (pruned)"}),
            "As the seed's Fig. 6.7 (pruned)");
  EXPECT_EQ(FigureCaption({"kld.png", "\u2013 (the KLD each removal loses)"}),
            "Not in the seed: the KLD each removal loses");
  EXPECT_EQ(FigureCaption({"memory.png", "\u2013 memory"}), "Not in the seed: memory");
}

TEST(Book, TheShippedBookLoadsInBothProfiles) {
  const Book book = LoadBook(kSource + "/book/chapter6.yaml");
  ASSERT_GE(book.experiments.size(), 5u);
  int quick = 0, full = 0, claims = 0;
  for (const BookExperiment& e : book.experiments) {
    quick += e.quick_spec.empty() ? 0 : 1;
    full += e.full_spec.empty() ? 0 : 1;
    claims += static_cast<int>(e.claims.size());
  }
  EXPECT_GE(quick, 4);
  EXPECT_EQ(full, static_cast<int>(book.experiments.size()));
  EXPECT_GE(claims, 12);
}

// A claim on a log replayed once can only be "inconclusive": the shipped book replays each
// log as draws (replay --seed), one paired run per seed.
TEST(Book, TheShippedBookReplaysEachLogAsSeveralDraws) {
  const Book book = LoadBook(kSource + "/book/chapter6.yaml");
  int logs = 0;
  for (const BookExperiment& e : book.experiments) {
    for (const std::string& spec : {e.quick_spec, e.full_spec}) {
      if (spec.empty()) continue;
      const SweepSpec s = LoadSweepSpec(spec, MissingLogs::kRecord);
      for (const SweepSource& source : s.sources) {
        if (!source.is_log) continue;
        ++logs;
        EXPECT_TRUE(source.seeded) << spec << ": " << source.given;
        EXPECT_GE(s.seeds.size(), 5u) << spec;
      }
    }
  }
  EXPECT_GE(logs, 3);
}

// Tables of a sweep: pruned's nodes are 10 below standard's on each of three seeds, give or
// take one; its blur is the same give or take noise.
SweepTables Tables() {
  SweepTables t;
  const double nodes_diff[] = {-10.0, -11.0, -9.0};
  const double blur_diff[] = {0.2, -0.3, 0.1};
  for (int seed = 0; seed < 3; ++seed) {
    const std::string cell = "corridor_3-seed" + std::to_string(seed);
    t.runs.push_back({cell,
                      "corridor_3",
                      "standard",
                      seed,
                      {},
                      {{"nodes_final", 100.0 + seed}, {"blur/mean_cm", 3.0}}});
    t.runs.push_back({cell,
                      "corridor_3",
                      "pruned",
                      seed,
                      {},
                      {{"nodes_final", 100.0 + seed + nodes_diff[seed]},
                       {"blur/mean_cm", 3.0 + blur_diff[seed]}}});
  }
  return t;
}

TEST(Book, AVerdictFollowsTheIntervalOfThePairedDifferences) {
  const SweepTables t = Tables();
  BookClaim fewer{"fewer nodes", "nodes_final", "pruned", "standard", "", "", Expect::kLower, 0};
  std::vector<ClaimResult> r = JudgeClaim(fewer, t);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].source, "corridor_3");
  EXPECT_EQ(r[0].difference.n, 3);
  EXPECT_NEAR(*r[0].difference.mean, -10.0, 1e-12);
  EXPECT_EQ(r[0].verdict, Verdict::kHolds);
  BookClaim more = fewer;
  more.expect = Expect::kHigher;
  EXPECT_EQ(JudgeClaim(more, t)[0].verdict, Verdict::kDoesNotHold);
  BookClaim sharper{"sharper", "blur/mean_cm", "pruned", "standard", "", "", Expect::kLower, 0};
  EXPECT_EQ(JudgeClaim(sharper, t)[0].verdict, Verdict::kInconclusive);
  BookClaim report = fewer;
  report.expect = Expect::kReport;
  EXPECT_EQ(JudgeClaim(report, t)[0].verdict, Verdict::kReported);
  // One seed has no interval: inconclusive, whatever the difference.
  SweepTables one = t;
  one.runs.resize(2);
  EXPECT_EQ(JudgeClaim(fewer, one)[0].verdict, Verdict::kInconclusive);
  BookClaim absent = fewer;
  absent.figure = "relations/trans_mean_m";
  EXPECT_TRUE(JudgeClaim(absent, t).empty());
}

TEST(Book, TheMarkdownNamesTheProfileAndEachVerdict) {
  BookExperiment e;
  e.id = "corridor";
  e.title = "§6.1 the corridor";
  e.quick_spec = "q.yaml";
  e.full_spec = "f.yaml";
  const BookClaim fewer{"fewer nodes", "nodes_final", "pruned",       "standard",
                        "constant",    "Fig. 6.1",    Expect::kLower, 0};
  BookOutcome o;
  o.profile = "quick";
  o.commit = "abc1234";
  o.day = "2026-12-03";
  ExperimentResult& r = o.experiments.emplace_back();
  r.experiment = &e;
  r.dir = "corridor";
  r.tables = Tables();
  r.claims = JudgeClaim(fewer, r.tables);
  BookClaim shown = fewer;
  shown.expect = Expect::kReport;
  for (ClaimResult& c : JudgeClaim(shown, r.tables)) r.claims.push_back(c);
  const std::string md = BookMarkdown(o);
  EXPECT_NE(md.find("pruned beside standard, no verdict"), std::string::npos) << md;
  EXPECT_EQ(md.find("reported than"), std::string::npos) << md;
  EXPECT_NE(md.find("profile quick: fewer seeds"), std::string::npos) << md;
  EXPECT_NE(md.find("holds at 95 %"), std::string::npos) << md;
  EXPECT_NE(md.find("| seeds or draws |"), std::string::npos) << md;  // a log's n is its draws
  EXPECT_NE(md.find("constant (Fig. 6.1)"), std::string::npos) << md;
  EXPECT_NE(md.find("abc1234, 2026-12-03"), std::string::npos) << md;
  EXPECT_EQ(md.find("As the seed's"), std::string::npos) << md;
  r.figures = {{"corridor/cells/corridor_3-seed0/pruned/map.png", "Fig. 6.7 (pruned)"}};
  EXPECT_NE(BookMarkdown(o).find("![Fig. 6.7 (pruned)](corridor/cells/corridor_3-seed0/pruned/"
                                 "map.png)\n\n*As the seed's Fig. 6.7 (pruned)*"),
            std::string::npos)
      << BookMarkdown(o);
}

// An experiment on a public log the project does not ship: without the log it loads, says
// which log is missing, and the book reports it as not run; unmarked, a missing log is an error.
TEST(Book, AnExperimentOnAnAbsentPublicLogIsNotRun) {
  Write("log_spec.yaml", "logs: [{log: absent-corrected.log.gz}]\nmodes: [standard, pruned]\n");
  const std::string text =
      "experiments:\n"
      "  - id: killian\n"
      "    title: Killian Court\n"
      "    full: log_spec.yaml\n"
      "    logs_optional: true\n"
      "    get: somewhere public\n"
      "    claims:\n"
      "      - {claim: consistent, figure: ate_rmse_m, mode: pruned, expect: report}\n";
  const Book book = LoadBook(Write("optional.yaml", text));
  ASSERT_EQ(book.experiments.size(), 1u);
  const BookExperiment& e = book.experiments[0];
  ASSERT_EQ(e.full_missing.size(), 1u);
  EXPECT_NE(e.full_missing[0].find("absent-corrected.log.gz"), std::string::npos);
  EXPECT_EQ(e.get, "somewhere public");
  std::string strict = text;
  strict.erase(strict.find("    logs_optional: true\n"), 24);
  try {
    LoadBook(Write("strict.yaml", strict));
    ADD_FAILURE() << "a missing log loaded without logs_optional";
  } catch (const InputError& error) {
    EXPECT_NE(error.file().find("log_spec.yaml"), std::string::npos) << error.what();
    EXPECT_EQ(error.field(), "logs[0].log") << error.what();
    EXPECT_NE(std::string(error.what()).find("no such log"), std::string::npos) << error.what();
  }

  BookOutcome o;
  o.profile = "full";
  ExperimentResult& r = o.experiments.emplace_back();
  r.experiment = &e;
  r.not_run = "its log is not here: x";
  const std::string md = BookMarkdown(o);
  EXPECT_NE(md.find("**Not run**: its log is not here: x"), std::string::npos) << md;
}

}  // namespace
}  // namespace lifelong::eval
