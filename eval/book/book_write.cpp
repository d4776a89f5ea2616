// The results book of `lifelong reproduce`: DIR/results.md and DIR/index.html
// (eval/book/book.hpp). Every table names its profile; a quick book says it rests on fewer seeds
// and shorter scenarios than the seed's experiments.
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "eval/book/book.hpp"
#include "eval/common/html.hpp"
#include "io/atomic_file.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

/// "mean [low, high]", "mean" with one value, "–" with none.
std::string Stats(const SampleStats& s) {
  if (!s.mean) return "–";
  std::string out = Num(*s.mean);
  if (s.ci95_low && s.ci95_high) out += " [" + Num(*s.ci95_low) + ", " + Num(*s.ci95_high) + "]";
  return out;
}

std::string ExpectText(Expect e) {
  return e == Expect::kLower ? "lower" : e == Expect::kHigher ? "higher" : "reported";
}

std::string ProfileNote(const BookOutcome& o) {
  if (o.profile == "quick") {
    return "profile quick: fewer seeds and shorter scenarios than the seed's experiments";
  }
  return "profile " + o.profile;
}

/// The table of one experiment's claims: one row per claim and source.
struct Row {
  std::string claim, source, seed, expect, baseline, mode, difference, n, verdict;
};

std::vector<Row> Rows(const ExperimentResult& e) {
  std::vector<Row> rows;
  for (const ClaimResult& r : e.claims) {
    const BookClaim& c = *r.claim;
    std::string seed = c.seed_value;
    if (!c.seed_where.empty())
      seed += (seed.empty() ? "" : " (") + c.seed_where + (seed.empty() ? "" : ")");
    rows.push_back({c.claim + " (" + c.figure + ")", SourceName(r.source), seed,
                    c.expect == Expect::kReport
                        ? c.mode + " beside " + c.baseline + ", no verdict"
                        : c.mode + " " + ExpectText(c.expect) + " than " + c.baseline,
                    c.baseline + ": " + Stats(r.baseline), c.mode + ": " + Stats(r.mode),
                    Stats(r.difference), std::to_string(r.difference.n), VerdictText(r.verdict)});
  }
  return rows;
}

// How a verdict comes about, for the top of both pages.
constexpr const char* kHowJudged =
    "is judged on the per-seed differences between two modes of the same simulated world, "
    "route and noise, or of the same draw of a log (its odometry perturbed by about 1 %, "
    "replay --seed): it holds when the 95 % interval of the mean difference lies on the "
    "expected side of 0.";

const char* kHeader[] = {"claim (figure)",
                         "scenario or log",
                         "the seed",
                         "expected",
                         "baseline, mean [95 %]",
                         "mode, mean [95 %]",
                         "difference per seed [95 %]",
                         "seeds or draws",
                         "verdict"};

}  // namespace

std::string FigureCaption(const BookFigure& figure) {
  // A figure the seed has no counterpart of is listed with "– (what it shows)".
  const std::string dash = "\u2013 ";
  if (figure.seed.rfind(dash, 0) != 0) return "As the seed's " + figure.seed;
  std::string what = figure.seed.substr(dash.size());
  if (what.size() >= 2 && what.front() == '(' && what.back() == ')') {
    what = what.substr(1, what.size() - 2);
  }
  return "Not in the seed: " + what;
}

std::string SourceName(const std::string& source) {
  const fs::path p(source);
  return p.extension() == ".yaml" ? p.stem().string() : p.filename().string();
}

std::string BookMarkdown(const BookOutcome& o) {
  std::ostringstream md;
  md << "# The seed's chapter 6, reproduced\n\n"
     << "`lifelong reproduce --profile " << o.profile << "` at " << o.commit << ", " << o.day
     << ". Each claim of Kretzschmar 2009, chapter 6, " << kHowJudged << " " << ProfileNote(o)
     << ".\n";
  for (const ExperimentResult& e : o.experiments) {
    md << "\n## " << e.experiment->title << "\n\n";
    if (!e.not_run.empty()) {
      md << "**Not run**: " << e.not_run << ".\n";
      continue;
    }
    if (e.dir.empty()) {
      md << "Not in the " << o.profile << " profile.\n";
      continue;
    }
    md << ProfileNote(o) << "; the sweep: `" << e.dir << "/` (`report.html`, `runs.csv`).";
    if (!e.tables.missing.empty()) {
      md << " **" << e.tables.missing.size() << " cells have no result.**";
    }
    md << "\n\n|";
    for (const char* h : kHeader) md << " " << h << " |";
    md << "\n|";
    for (std::size_t i = 0; i < std::size(kHeader); ++i) md << "---|";
    md << "\n";
    for (const Row& r : Rows(e)) {
      md << "| " << r.claim << " | " << r.source << " | " << r.seed << " | " << r.expect << " | "
         << r.baseline << " | " << r.mode << " | " << r.difference << " | " << r.n << " | "
         << r.verdict << " |\n";
    }
    for (const std::string& chart : e.charts) md << "\n![" << chart << "](" << chart << ")\n";
    for (const BookFigure& f : e.figures) {
      md << "\n![" << f.seed << "](" << f.file << ")\n\n*" << FigureCaption(f) << "* (`" << f.file
         << "`)\n";
    }
  }
  return md.str();
}

void WriteBook(const BookOutcome& o, const std::string& dir) {
  io::WriteFileAtomically(dir + "/results.md", BookMarkdown(o));
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>The seed's chapter 6, "
       "reproduced</title>\n<style>body{font-family:sans-serif;max-width:1200px;margin:auto}"
       "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:3px 6px}"
       ".holds{background:#d8f5d8}.not{background:#f8d8d8}.inc{background:#f3f3d0}"
       // The sweep's charts two to a row; a figure of the seed's at its own width, up to the
       // page's (the seed's layouts are three panels wide).
       "img{max-width:560px;margin:4px}figure{display:inline-block;margin:4px;max-width:100%}"
       "figure img{max-width:100%}"
       "figcaption{font-size:90%;color:#444}</style></head><body>\n"
    << "<h1>The seed's chapter 6, reproduced</h1>\n<p><code>lifelong reproduce --profile "
    << HtmlEscape(o.profile) << "</code> at " << HtmlEscape(o.commit) << ", " << HtmlEscape(o.day)
    << ". Each claim " << kHowJudged << " <b>" << HtmlEscape(ProfileNote(o))
    << ".</b> The same in <a href=\"results.md\">results.md</a>.</p>\n";
  for (const ExperimentResult& e : o.experiments) {
    h << "<h2>" << HtmlEscape(e.experiment->title) << "</h2>\n";
    if (!e.not_run.empty()) {
      h << "<p><b>Not run</b>: " << HtmlEscape(e.not_run) << ".</p>\n";
      continue;
    }
    if (e.dir.empty()) {
      h << "<p>Not in the " << HtmlEscape(o.profile) << " profile.</p>\n";
      continue;
    }
    h << "<p>" << HtmlEscape(ProfileNote(o)) << "; the sweep: <a href=\"" << HtmlEscape(e.dir)
      << "/report.html\">" << HtmlEscape(e.dir) << "/report.html</a>";
    if (!e.tables.missing.empty()) {
      h << " <b>(" << e.tables.missing.size() << " cells have no result)</b>";
    }
    h << ".</p>\n<table><tr>";
    for (const char* head : kHeader) h << "<th>" << head << "</th>";
    h << "</tr>\n";
    for (const Row& r : Rows(e)) {
      const std::string cls = r.verdict == VerdictText(Verdict::kHolds)          ? "holds"
                              : r.verdict == VerdictText(Verdict::kDoesNotHold)  ? "not"
                              : r.verdict == VerdictText(Verdict::kInconclusive) ? "inc"
                                                                                 : "";
      h << "<tr>";
      for (const std::string* cell :
           {&r.claim, &r.source, &r.seed, &r.expect, &r.baseline, &r.mode, &r.difference, &r.n}) {
        h << "<td>" << HtmlEscape(*cell) << "</td>";
      }
      h << "<td class=\"" << cls << "\">" << HtmlEscape(r.verdict) << "</td></tr>\n";
    }
    h << "</table>\n";
    for (const std::string& chart : e.charts) {
      h << "<img src=\"" << HtmlEscape(chart) << "\" alt=\"" << HtmlEscape(chart) << "\">\n";
    }
    for (const BookFigure& f : e.figures) {
      h << "<figure><img src=\"" << HtmlEscape(f.file) << "\" alt=\"" << HtmlEscape(f.seed)
        << "\"><figcaption>" << HtmlEscape(FigureCaption(f)) << " (" << HtmlEscape(f.file)
        << ")</figcaption></figure>\n";
    }
  }
  h << "</body></html>\n";
  io::WriteFileAtomically(dir + "/index.html", h.str());
}

}  // namespace lifelong::eval
