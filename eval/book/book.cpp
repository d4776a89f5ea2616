// Reading a BOOK (eval/book/book.hpp).
#include "eval/book/book.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include "eval/sweep/sweep_spec.hpp"
#include "sensor/input_error.hpp"
#include "sim/yaml_fields.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

Expect ParseExpect(sim::Fields& f) {
  const std::string e = f.String("expect");
  if (e == "lower") return Expect::kLower;
  if (e == "higher") return Expect::kHigher;
  if (e == "report") return Expect::kReport;
  f.FailAt("expect", "expected lower, higher or report, not '" + e + "'");
}

/// A SPEC named relative to the BOOK, loaded (so its errors surface now), made absolute.
std::string Spec(sim::Fields& f, const std::string& key, const fs::path& dir, MissingLogs missing,
                 SweepSpec* spec) {
  const fs::path p = (dir / f.String(key)).lexically_normal();
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) f.FailAt(key, "no such sweep SPEC: " + p.string());
  *spec = LoadSweepSpec(p.string(), missing);
  return p.string();
}

BookClaim Claim(const std::string& file, const YAML::Node& n, const std::string& field,
                const std::vector<SweepSpec>& specs) {
  sim::Fields f(file, n, field);
  BookClaim c;
  c.line = sim::LineOf(n);
  c.claim = f.String("claim");
  c.figure = f.String("figure");
  c.mode = f.String("mode");
  c.baseline = f.Has("baseline") ? f.String("baseline") : specs.front().baseline;
  c.expect = ParseExpect(f);
  c.seed_value = f.Has("seed") ? f.String("seed") : "";
  c.seed_where = f.Has("where") ? f.String("where") : "";
  f.Finish();
  for (const SweepSpec& s : specs) {
    for (const std::string& m : {c.mode, c.baseline}) {
      if (std::find(s.modes.begin(), s.modes.end(), m) == s.modes.end()) {
        f.FailAt(m == c.mode ? "mode" : "baseline", "the sweep " + s.file + " runs no mode " + m);
      }
    }
  }
  if (c.mode == c.baseline) f.FailAt("baseline", "a claim compares two different modes");
  return c;
}

/// The experiment's `figures`: each a PNG relative to a cell's directory, inside it.
std::vector<BookFigure> Figures(const std::string& file, sim::Fields& f) {
  if (!f.Has("figures")) {
    return {{"time_per_obs.png", "runtime per scan over the run (Fig. 6.1-6.4)"},
            {"nodes.png", "nodes over the run (Fig. 6.1, 6.2)"}};
  }
  const YAML::Node list = f.Required("figures");
  if (!list.IsSequence()) f.FailAt("figures", "expected a list of {file, seed}");
  std::vector<BookFigure> out;
  for (std::size_t k = 0; k < list.size(); ++k) {
    sim::Fields g(file, list[k], f.Name("figures") + "[" + std::to_string(k) + "]");
    BookFigure b{g.String("file"), g.String("seed")};
    g.Finish();
    const fs::path p(b.file);
    const bool inside = p.is_relative() && std::none_of(p.begin(), p.end(), [](const fs::path& c) {
                          return c == "..";
                        });
    if (!inside || p.extension() != ".png") {
      g.FailAt("file", "expected a .png inside a cell's directory, not '" + b.file + "'");
    }
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace

Book LoadBook(const std::string& path) {
  Book book;
  book.file = path;
  const YAML::Node root = sim::ParseYamlFile(path);
  const fs::path dir = fs::absolute(fs::path(path)).parent_path();
  sim::Fields top(path, root, "");
  const YAML::Node list = top.Required("experiments");
  top.Finish();
  if (!list.IsSequence() || list.size() == 0) {
    throw InputError(path, sim::LineOf(list), "experiments", "expected a non-empty list");
  }
  const std::regex id_pattern("[a-z0-9_-]+");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string field = "experiments[" + std::to_string(i) + "]";
    sim::Fields f(path, list[i], field);
    BookExperiment e;
    e.id = f.String("id");
    if (!std::regex_match(e.id, id_pattern)) f.FailAt("id", "expected [a-z0-9_-]+");
    if (!ids.insert(e.id).second) f.FailAt("id", "given twice");
    e.title = f.String("title");
    e.figures = Figures(path, f);
    const bool optional = f.Bool("logs_optional", false);
    if (f.Has("get")) e.get = f.String("get");
    const MissingLogs missing = optional ? MissingLogs::kRecord : MissingLogs::kRefuse;
    std::vector<SweepSpec> specs;
    for (const char* profile : {"quick", "full"}) {
      if (!f.Has(profile)) continue;
      const bool quick = profile == std::string("quick");
      (quick ? e.quick_spec : e.full_spec) = Spec(f, profile, dir, missing, &specs.emplace_back());
      (quick ? e.quick_missing : e.full_missing) = specs.back().missing_logs;
    }
    if (specs.empty()) f.FailAt("quick", "an experiment needs a quick or a full SPEC, or both");
    const YAML::Node claims = f.Required("claims");
    if (!claims.IsSequence() || claims.size() == 0) f.FailAt("claims", "expected a non-empty list");
    for (std::size_t k = 0; k < claims.size(); ++k) {
      e.claims.push_back(
          Claim(path, claims[k], f.Name("claims") + "[" + std::to_string(k) + "]", specs));
    }
    f.Finish();
    book.experiments.push_back(std::move(e));
  }
  return book;
}

std::string VerdictText(Verdict v) {
  switch (v) {
    case Verdict::kHolds:
      return "holds at 95 %";
    case Verdict::kDoesNotHold:
      return "does not hold";
    case Verdict::kInconclusive:
      return "inconclusive";
    case Verdict::kReported:
      return "reported";
  }
  return "";
}

std::vector<ClaimResult> JudgeClaim(const BookClaim& claim, const SweepTables& tables) {
  // Per source: the cells (scenario x seed x setting) that ran both modes with the figure.
  struct Pair {
    std::optional<double> base, mode;
  };
  std::vector<std::string> sources;
  std::map<std::string, std::map<std::string, Pair>> by_source;  // source -> cell -> pair
  for (const SweepRunRow& r : tables.runs) {
    if (r.mode != claim.mode && r.mode != claim.baseline) continue;
    const auto it = r.figures.find(claim.figure);
    if (it == r.figures.end()) continue;
    if (!by_source.count(r.source)) sources.push_back(r.source);
    Pair& p = by_source[r.source][r.cell];
    (r.mode == claim.mode ? p.mode : p.base) = it->second;
  }
  std::vector<ClaimResult> out;
  for (const std::string& source : sources) {
    std::vector<double> base, mode, diff;
    for (const auto& [cell, p] : by_source[source]) {
      if (p.base) base.push_back(*p.base);
      if (p.mode) mode.push_back(*p.mode);
      if (p.base && p.mode) diff.push_back(*p.mode - *p.base);
    }
    ClaimResult r;
    r.claim = &claim;
    r.source = source;
    r.baseline = ComputeStats(base);
    r.mode = ComputeStats(mode);
    r.difference = ComputeStats(diff);
    const SampleStats& d = r.difference;
    if (claim.expect == Expect::kReport) {
      r.verdict = Verdict::kReported;
    } else if (d.ci95_low && d.ci95_high) {
      const bool below = *d.ci95_high<0.0, above = *d.ci95_low> 0.0;
      const bool want_below = claim.expect == Expect::kLower;
      if (below || above) r.verdict = below == want_below ? Verdict::kHolds : Verdict::kDoesNotHold;
    }
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace lifelong::eval
