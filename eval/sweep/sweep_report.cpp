#include "eval/sweep/sweep_report.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <map>
#include <sstream>

#include "eval/common/gnuplot_run.hpp"
#include "eval/common/html.hpp"
#include "eval/figures/mode_colors.hpp"
#include "eval/figures/plots.hpp"
#include "io/atomic_file.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

std::string Num(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

std::string Exact(double v) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof(buf), v).ptr);
}

std::string Quote(const std::string& s, char q) {  // q doubled inside, no escapes
  std::string out(1, q);
  for (char c : s) out += c == q ? std::string(2, q) : std::string(1, c);
  return out + q;
}

std::string SafeName(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

// "corridor_3.yaml gain_threshold_bits=5": one x position of a chart.
std::string GroupLabel(const SweepStatsRow& r) {
  std::string label = fs::path(r.source).filename().string();
  for (const auto& [k, v] : r.settings) label += " " + k.substr(k.rfind('.') + 1) + "=" + v;
  return label;
}

// One chart's script, plot_data/<name>.gp (drawing the temporary of <name>.png), and its
// data: x = source × setting, a series per mode (offset a little), mean ± 95 %. Returns the
// name, or "" when no mode has the figure.
std::string ChartScript(const SweepTables& t, const std::string& figure, const std::string& dir,
                        const std::string& terminal) {
  std::vector<std::string> labels;
  std::map<std::string, std::ostringstream> data;  // mode -> rows
  for (const SweepStatsRow& r : t.aggregate) {
    const std::string label = GroupLabel(r);
    auto at = std::find(labels.begin(), labels.end(), label);
    const std::size_t x = static_cast<std::size_t>(at - labels.begin());
    if (at == labels.end()) labels.push_back(label);
    const auto it = r.figures.find(figure);
    if (it == r.figures.end() || !it->second.mean) continue;
    const SampleStats& s = it->second;
    data[r.mode] << x << " " << Exact(*s.mean) << " " << Exact(s.ci95_low.value_or(*s.mean)) << " "
                 << Exact(s.ci95_high.value_or(*s.mean)) << "\n";
  }
  if (data.empty()) return "";
  const std::string stem = "sweep_" + SafeName(figure);
  std::ostringstream gp;
  const std::string tmp = io::TempPathFor((fs::path(dir) / (stem + ".png")).string());
  gp << "set terminal " << terminal << " noenhanced size 800,450\nset output "
     << Quote(fs::path(tmp).filename().string(), '\'') << "\nset ylabel " << Quote(figure, '\'')
     << "\nset grid\nset key outside top center horizontal\nset offsets 0.5, 0.5, 0, 0\n"
     << "set yrange [0:*]\n"
     << "set xtics rotate by -20 (";
  for (std::size_t i = 0; i < labels.size(); ++i) {
    gp << (i ? ", " : "") << Quote(labels[i], '\'') << " " << i;
  }
  gp << ")\nplot ";
  const double width = 0.5 / static_cast<double>(t.plan.modes.size());
  int k = 0;
  for (std::size_t m = 0; m < t.plan.modes.size(); ++m) {
    const std::string& mode = t.plan.modes[m];
    if (!data.count(mode)) continue;
    const std::string file = "plot_data/" + stem + "_" + SafeName(mode) + ".dat";
    io::WriteFileAtomically((fs::path(dir) / file).string(), data[mode].str());
    const double offset = (static_cast<double>(m) - 0.5 * (t.plan.modes.size() - 1)) * width;
    gp << (k++ ? ", " : "") << Quote(file, '\'') << " using ($1+" << Exact(offset)
       << "):2:3:4 with yerrorbars pt 7 ps 1.2 lw 2 lc rgb " << Quote(ModeColourHex(mode), '\'')
       << " title " << Quote(mode, '\'');
  }
  gp << "\n";
  gp << "unset output\n";
  io::WriteFileAtomically((fs::path(dir) / "plot_data" / (stem + ".gp")).string(), gp.str());
  return stem;
}

/// The key figures' charts, drawn by the one gnuplot runner (eval/common/gnuplot_run.hpp);
/// the PNG names of those drawn.
std::vector<std::string> Charts(const SweepTables& t, const std::string& dir,
                                const std::string& gnuplot, const std::string& terminal) {
  fs::create_directories(fs::path(dir) / "plot_data");
  std::vector<std::string> names;
  for (const std::string& f : SweepKeyFigures()) {
    const std::string name = ChartScript(t, f, dir, terminal);
    if (!name.empty()) names.push_back(name);
  }
  std::vector<std::string> charts;
  for (const std::string& name : RunGnuplotScripts(gnuplot, dir, names).drawn) {
    const std::string png = (fs::path(dir) / (name + ".png")).string();
    io::CommitTempFile(io::TempPathFor(png), png);
    charts.push_back(name + ".png");
  }
  return charts;
}

std::string Table(const SweepTables& t, const std::vector<SweepStatsRow>& rows,
                  const std::string& caption) {
  std::ostringstream h;
  h << "<h2>" << HtmlEscape(caption) << "</h2>\n<table>\n<tr><th>source</th>";
  for (const std::string& k : t.plan.setting_keys) h << "<th>" << HtmlEscape(k) << "</th>";
  h << "<th>mode</th><th>n</th>";
  for (const std::string& f : SweepKeyFigures()) h << "<th>" << HtmlEscape(f) << "</th>";
  h << "</tr>\n";
  for (const SweepStatsRow& r : rows) {
    h << "<tr><td>" << HtmlEscape(r.source) << "</td>";
    for (const auto& s : r.settings) h << "<td>" << HtmlEscape(s.second) << "</td>";
    h << "<td>" << HtmlEscape(r.mode) << "</td><td>" << r.n << "</td>";
    for (const std::string& f : SweepKeyFigures()) {
      const auto it = r.figures.find(f);
      h << "<td>";
      if (it != r.figures.end() && it->second.mean) {
        const SampleStats& s = it->second;
        h << Num(*s.mean);
        if (s.ci95_low) h << " [" << Num(*s.ci95_low) << ", " << Num(*s.ci95_high) << "]";
      }
      h << "</td>";
    }
    h << "</tr>\n";
  }
  return h.str() + "</table>\n";
}

}  // namespace

const std::vector<std::string>& SweepKeyFigures() {
  static const std::vector<std::string> figures = {"time_per_obs_ms/mean", "nodes_final",
                                                   "blur/mean_cm", "ate_rmse_m"};
  return figures;
}

std::vector<std::string> WriteSweepReport(const SweepTables& t, const std::string& dir,
                                          const std::string& gnuplot) {
  std::vector<std::string> charts;
  std::string terminal;
  const bool have_gnuplot = GnuplotAvailable(gnuplot, &terminal);
  if (have_gnuplot) charts = Charts(t, dir, gnuplot, terminal);
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>lifelong sweep</title>\n"
    << "<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
    << "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}img{max-width:100%}"
    << "</style></head><body>\n<h1>Sweep " << HtmlEscape(t.plan.spec) << "</h1>\n<p>"
    << t.plan.cells.size() << " cells, " << t.plan.cells.size() - t.missing.size()
    << " with results; modes";
  for (const std::string& m : t.plan.modes) h << " " << HtmlEscape(m);
  h << " (baseline " << HtmlEscape(t.plan.baseline) << "). Intervals: 95 % Student t over "
    << "the seeds; [low, high] is absent when n = 1.</p>\n";
  if (!t.missing.empty()) {
    h << "<p>Cells without a current result (failed, not run or from other inputs):";
    for (const std::string& m : t.missing) h << " " << HtmlEscape(m);
    h << "</p>\n";
  }
  if (!have_gnuplot)
    h << "<p>No charts: gnuplot (" << HtmlEscape(gnuplot) << ") did not run.</p>\n";
  for (const std::string& c : charts) {
    h << "<p><a href=\"" << HtmlEscape(c) << "\"><img src=\"" << HtmlEscape(c) << "\"></a></p>\n";
  }
  h << Table(t, t.aggregate, "Mean and 95 % interval per source, setting and mode")
    << Table(t, t.paired, "Paired difference mode − " + t.plan.baseline + " per seed")
    << "<h2>Files</h2>\n<p><a href=\"runs.csv\">runs.csv</a> <a href=\"aggregate.csv\">"
    << "aggregate.csv</a> <a href=\"paired.csv\">paired.csv</a> <a href=\"sweep.json\">"
    << "sweep.json</a></p>\n<ul>\n";
  for (const SweepPlanCell& c : t.plan.cells) {
    h << "<li><a href=\"cells/" << HtmlEscape(c.name) << "/report.html\">" << HtmlEscape(c.name)
      << "</a></li>\n";
  }
  h << "</ul>\n</body></html>\n";
  io::WriteFileAtomically((fs::path(dir) / "report.html").string(), h.str());
  return charts;
}

}  // namespace lifelong::eval
