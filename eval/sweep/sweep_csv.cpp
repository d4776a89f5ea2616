// The CSV files of `lifelong sweep collect` (eval/sweep/sweep_collect.hpp).
#include <charconv>
#include <filesystem>
#include <sstream>

#include "eval/sweep/sweep_collect.hpp"
#include "io/atomic_file.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

/// Shortest text that reads back to exactly `v`.
std::string Number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

std::string Field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string Optional(const std::optional<double>& v) { return v ? Number(*v) : ""; }

class Csv {
 public:
  void Cell(const std::string& s) { line_ += (line_.empty() ? "" : ",") + Field(s); }
  void End() {
    out_ << line_ << "\n";
    line_.clear();
  }
  std::string str() const { return out_.str(); }

 private:
  std::ostringstream out_;
  std::string line_;
};

std::string RunsCsv(const SweepTables& t) {
  Csv csv;
  for (const char* h : {"cell", "source", "seed", "mode"}) csv.Cell(h);
  for (const std::string& k : t.plan.setting_keys) csv.Cell(k);
  for (const std::string& f : t.figures) csv.Cell(f);
  csv.End();
  for (const SweepRunRow& r : t.runs) {
    csv.Cell(r.cell);
    csv.Cell(r.source);
    csv.Cell(r.seed ? std::to_string(*r.seed) : "");
    csv.Cell(r.mode);
    for (const auto& setting : r.settings) csv.Cell(setting.second);
    for (const std::string& f : t.figures) {
      const auto it = r.figures.find(f);
      csv.Cell(it == r.figures.end() ? "" : Number(it->second));
    }
    csv.End();
  }
  return csv.str();
}

std::string StatsCsv(const SweepTables& t, const std::vector<SweepStatsRow>& rows, bool paired) {
  Csv csv;
  csv.Cell("source");
  csv.Cell("mode");
  if (paired) csv.Cell("baseline");
  for (const std::string& k : t.plan.setting_keys) csv.Cell(k);
  csv.Cell("n");
  for (const std::string& f : t.figures) {
    for (const char* s : {"/mean", "/std", "/ci95_low", "/ci95_high", "/n"}) csv.Cell(f + s);
  }
  csv.End();
  for (const SweepStatsRow& r : rows) {
    csv.Cell(r.source);
    csv.Cell(r.mode);
    if (paired) csv.Cell(t.plan.baseline);
    for (const auto& setting : r.settings) csv.Cell(setting.second);
    csv.Cell(std::to_string(r.n));
    for (const std::string& f : t.figures) {
      const auto it = r.figures.find(f);
      const SampleStats s = it == r.figures.end() ? SampleStats{} : it->second;
      for (const auto& v : {s.mean, s.std, s.ci95_low, s.ci95_high}) csv.Cell(Optional(v));
      csv.Cell(s.n > 0 ? std::to_string(s.n) : "");
    }
    csv.End();
  }
  return csv.str();
}

}  // namespace

void WriteSweepCsvs(const SweepTables& tables, const std::string& dir) {
  const fs::path d(dir);
  io::WriteFileAtomically((d / "runs.csv").string(), RunsCsv(tables));
  io::WriteFileAtomically((d / "aggregate.csv").string(),
                          StatsCsv(tables, tables.aggregate, false));
  io::WriteFileAtomically((d / "paired.csv").string(), StatsCsv(tables, tables.paired, true));
}

}  // namespace lifelong::eval
