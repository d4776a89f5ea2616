#include "eval/figures/plots.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>
#include <utility>

#include "io/atomic_file.hpp"

#include "eval/common/gnuplot_run.hpp"
#include "eval/common/mode_order.hpp"
#include "eval/figures/mode_colors.hpp"
#include "eval/metrics/metrics.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

constexpr double kMiB = 1024.0 * 1024.0;  // bytes; rss_mb is in the same unit (resources.hpp)

/// gnuplot single-quoted string: no escapes, a quote is doubled.
std::string GpQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string SafeName(const std::string& mode) {
  std::string out;
  for (char c : mode) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-') ? c : '_';
  return out;
}

std::vector<double> MovingAverage(const std::vector<double>& v, int window) {
  std::vector<double> out(v.size());
  double sum = 0.0;
  const std::size_t w = static_cast<std::size_t>(std::max(window, 1));
  for (std::size_t i = 0; i < v.size(); ++i) {
    sum += v[i];
    if (i >= w) sum -= v[i - w];
    out[i] = sum / static_cast<double>(std::min(i + 1, w));
  }
  return out;
}

/// One gnuplot plot clause per (colour "#rrggbb", data file, title).
using Clauses =
    std::function<std::string(const std::string&, const std::string&, const std::string&)>;

struct Panel {
  std::string ylabel;
  bool log_y = false;
  Clauses clauses;
  std::string yrange;  ///< e.g. "[0:1.05]"; empty: autoscale
  std::string note;    ///< written across the panel, e.g. "no closures"; empty: none
};

struct Figure {
  std::string name;  ///< file stem
  std::string xlabel;
  std::vector<Panel> panels;                  ///< stacked top to bottom, sharing the x axis
  std::map<std::string, std::string> files;   ///< mode -> its data file
  std::map<std::string, std::string> titles;  ///< mode -> legend entry; absent: the mode
  bool side_by_side = false;  ///< panels left to right (the seed's layout), else stacked
};

/// Writes a plot_data file atomically; a failure becomes the result's error (figures are
/// optional, a run goes on without them).
bool WritePlotFile(const fs::path& path, const std::string& text, PlotResult* result) {
  try {
    io::WriteFileAtomically(path.string(), text);
    return true;
  } catch (const std::exception& e) {
    result->error = e.what();
    return false;
  }
}

/// The (mode, data file) pairs in the run's mode order (eval/common/mode_order.hpp).
std::vector<std::pair<std::string, std::string>> InLegendOrder(
    const std::map<std::string, std::string>& data_files, const std::vector<std::string>& order) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& mode : ModesInOrder(data_files, order)) {
    out.emplace_back(mode, data_files.at(mode));
  }
  return out;
}

/// Writes the figure's script (plot_data/<name>.gp; drawing <name>.tmp.png from out_dir).
bool WriteScript(const Figure& f, const std::string& out_dir, const std::string& terminal,
                 const PlotConfig& c, PlotResult* result) {
  const std::string tmp = io::TempPathFor((fs::path(out_dir) / (f.name + ".png")).string());
  std::ostringstream gp;
  const auto n = static_cast<int>(f.panels.size());
  int width = c.width_px, height = n > 1 ? c.height_px * 3 / 2 : c.height_px;  // px
  if (f.side_by_side) {
    width = c.width_px * n * 2 / 3;
    height = c.height_px * 4 / 5;
  }
  // `reset` and `unset output`: each script stands alone, run by itself or after others.
  gp << "reset\nset terminal " << terminal << " noenhanced size " << width << "," << height
     << "\nset output " << GpQuote(fs::path(tmp).filename().string()) << "\n"
     << "set xlabel " << GpQuote(f.xlabel) << "\nset grid\nset key top left\n";
  if (n > 1) {
    gp << "set multiplot layout " << (f.side_by_side ? 1 : n) << "," << (f.side_by_side ? n : 1)
       << "\n";
  }
  for (const Panel& panel : f.panels) {
    gp << "set ylabel " << GpQuote(panel.ylabel) << "\n"
       << (panel.log_y ? "set logscale y\n" : "unset logscale y\n")
       << (panel.yrange.empty() ? "set autoscale y\n" : "set yrange " + panel.yrange + "\n")
       << (panel.note.empty() ? "unset label 1\n"
                              : "set label 1 " + GpQuote(panel.note) +
                                    " at graph 0.5, graph 0.5 center font ',16'\n")
       << "plot ";
    int i = 0;
    for (const auto& [mode, file] : InLegendOrder(f.files, c.mode_order)) {
      const auto title = f.titles.find(mode);
      gp << (i++ ? ", \\\n     " : "")
         << panel.clauses(GpQuote(ModeColourHex(mode)),
                          GpQuote(fs::path(file).lexically_relative(out_dir).string()),
                          GpQuote(title == f.titles.end() ? mode : title->second));
    }
    gp << "\n";
  }
  if (n > 1) gp << "unset multiplot\n";
  gp << "unset output\n";
  return WritePlotFile(fs::path(out_dir) / "plot_data" / (f.name + ".gp"), gp.str(), result);
}

/// The directory that messages name: where the output will be read.
std::string NamedDir(const std::string& out_dir, const PlotConfig& c) {
  return c.named_dir.empty() ? out_dir : c.named_dir;
}

/// "figure loop_closing.png not drawn (gnuplot: DIR/plot_data/loop_closing.log)", or all.
std::string FailureMessage(const std::vector<FailedFigure>& failed, std::size_t drawn,
                           const std::string& named_dir) {
  if (drawn == 0) {
    return "gnuplot failed on every figure (see " +
           (fs::path(named_dir) / "plot_data" / "gnuplot.log").string() +
           " and the figure's .log beside it): no figures written";
  }
  std::string text;
  for (const FailedFigure& f : failed) {
    text += (text.empty() ? "" : "; ") + std::string("figure ") + f.figure + " not drawn (" +
            f.log + ")";
  }
  return text + "; the other " + std::to_string(drawn) + " written";
}

/// Writes the figures' scripts, runs them (eval/common/gnuplot_run.hpp: one process, each figure
/// alone when that fails) and renames each PNG drawn into place.
bool RenderAll(const std::vector<Figure>& figures, const std::string& out_dir,
               const std::string& terminal, const PlotConfig& c, PlotResult* result) {
  if (figures.empty()) return true;
  std::vector<std::string> names;
  for (const Figure& f : figures) {
    if (!WriteScript(f, out_dir, terminal, c, result)) return false;
    names.push_back(f.name);
  }
  const GnuplotRun run = RunGnuplotScripts(c.gnuplot, out_dir, names);
  bool ok = run.failed.empty();
  for (const std::string& name : run.drawn) {
    const fs::path png = fs::path(out_dir) / (name + ".png");
    try {
      io::CommitTempFile(io::TempPathFor(png.string()), png.string());
      result->files.push_back(png.string());
    } catch (const std::exception& e) {
      result->error = e.what();
      ok = false;
    }
  }
  for (const std::string& name : run.failed) {
    result->failed.push_back(
        {name + ".png", (fs::path(NamedDir(out_dir, c)) / "plot_data" / (name + ".log")).string()});
  }
  if (!run.failed.empty())
    result->error = FailureMessage(result->failed, run.drawn.size(), NamedDir(out_dir, c));
  return ok;
}

/// Checks gnuplot and prepares <out_dir>/plot_data; sets the error and returns "" if not.
std::string Prepare(const std::string& out_dir, const PlotConfig& c, PlotResult* r) {
  std::string terminal;
  if (!GnuplotAvailable(c.gnuplot, &terminal)) {
    r->error = "gnuplot not found (" + c.gnuplot + "): no figures written";
    return "";
  }
  std::error_code ec;
  fs::create_directories(fs::path(out_dir) / "plot_data", ec);
  if (ec) r->error = out_dir + "/plot_data: " + ec.message();
  r->gnuplot_found = !ec;
  return ec ? "" : terminal;
}

std::string Lines(const std::string& colour, const std::string& file, const std::string& title,
                  int col) {
  return file + " using 1:" + std::to_string(col) + " with lines lw 2 lc rgb " + colour +
         " title " + title;
}

/// A single-panel figure drawing column `col` of every mode's data as lines.
Figure LinesFigure(const std::string& name, const std::string& ylabel, int col, bool log_y) {
  return {name,
          "observation",
          {{ylabel, log_y,
            [col](const std::string& c, const std::string& f, const std::string& t) {
              return Lines(c, f, t, col);
            },
            "", ""}},
          {},
          {}};
}

// Each mode's timeline as plot_data/timeline_<mode>.dat into *files (mode -> data file);
// false with the error set when one cannot be written.
bool WriteTimelineData(const ModeTimelines& timelines, const std::string& out_dir,
                       const PlotConfig& config, std::map<std::string, std::string>* files,
                       PlotResult* r) {
  for (const auto& [mode, rows] : timelines) {
    std::vector<double> ms;
    for (const TimelineRow& row : rows) ms.push_back(row.time_ms);
    const std::vector<double> ma = MovingAverage(ms, config.moving_average);
    const fs::path p = fs::path(out_dir) / "plot_data" / ("timeline_" + SafeName(mode) + ".dat");
    std::ostringstream out;
    out << "# obs time_ms time_ms_moving_average nodes edges gamma cumulative_s rss_mib "
           "graph_mib\n";
    double cumulative_ms = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      cumulative_ms += rows[i].time_ms;
      out << rows[i].obs << ' ' << rows[i].time_ms << ' ' << ma[i] << ' ' << rows[i].nodes << ' '
          << rows[i].edges << ' ' << rows[i].gamma << ' ' << cumulative_ms / 1000.0 << ' '
          << rows[i].rss_mb << ' ' << static_cast<double>(rows[i].graph_bytes) / kMiB << '\n';
    }
    if (!WritePlotFile(p, out.str(), r)) return false;
    (*files)[mode] = p.string();
  }
  return true;
}

// The timeline figures (data files written into plot_data/); false with the error set
// when a data file cannot be written.
bool TimelineFigures(const ModeTimelines& timelines, const std::string& out_dir,
                     const PlotConfig& config, std::vector<Figure>* figures, PlotResult* r) {
  std::map<std::string, std::string> files;  // mode -> data file
  if (!WriteTimelineData(timelines, out_dir, config, &files, r)) return false;
  bool any_graph_bytes = false;  // a log axis needs a positive value
  for (const auto& [mode, rows] : timelines)
    for (const TimelineRow& row : rows) any_graph_bytes = any_graph_bytes || row.graph_bytes > 0;
  const std::string ma_label = std::to_string(config.moving_average);
  const Clauses dots_and_average = [](const std::string& c, const std::string& f,
                                      const std::string& t) {
    return f + " using 1:2 with dots lc rgb " + c + " notitle, " + Lines(c, f, t, 3);
  };
  std::vector<Figure> made = {
      {"time_per_obs",
       "observation",
       {{"time per observation [ms] (lines: moving average of " + ma_label + ")", config.log_time,
         dots_and_average, "", ""}},
       {},
       {}},
      LinesFigure("nodes", "nodes", 4, false),
      LinesFigure("edges", "edges", 5, false),
      LinesFigure("gamma", "gamma index e / (v (v-1) / 2)", 6, true),
      LinesFigure("cumulative_time", "cumulative mapper time [s]", 7, false),
      {"memory",
       "observation",
       {LinesFigure("", "resident memory of the process [MiB]", 8, false).panels[0],
        LinesFigure("", "memory held by the graph [MiB]", 9, any_graph_bytes).panels[0]},
       {},
       {}},
      // The seed's layouts: Figs. 6.1-6.4 (time per observation, nodes, edges) and Fig. 6.5
      // (edges, gamma index), panels side by side.
      {"performance",
       "observation",
       {LinesFigure("", "time per observation [ms] (moving average)", 3, config.log_time).panels[0],
        LinesFigure("", "number of nodes", 4, false).panels[0],
        LinesFigure("", "number of edges", 5, false).panels[0]},
       {},
       {},
       true},
      {"edges_gamma",
       "observation",
       {LinesFigure("", "edges", 5, false).panels[0],
        LinesFigure("", "gamma index", 6, true).panels[0]},
       {},
       {},
       true},
  };
  for (Figure& f : made) {
    f.files = files;
    figures->push_back(std::move(f));
  }
  return true;
}

bool KldFigure(const std::map<std::string, std::vector<double>>& kl_per_mode,
               const std::string& out_dir, std::vector<Figure>* figures, PlotResult* r) {
  Figure f{"kld",
           "marginalization",
           {{"KL divergence of the approximate clique [nats]", false,
             [](const std::string& c, const std::string& file, const std::string& t) {
               return file + " using 1:2 with points pt 7 ps 0.5 lc rgb " + c + " title " + t;
             },
             "", ""}},
           {},
           {}};
  for (const auto& [mode, kl] : kl_per_mode) {
    const fs::path p = fs::path(out_dir) / "plot_data" / ("kld_" + SafeName(mode) + ".dat");
    std::ostringstream out;
    out << "# marginalization kl_divergence\n";
    for (std::size_t i = 0; i < kl.size(); ++i) out << i << ' ' << kl[i] << '\n';
    if (!WritePlotFile(p, out.str(), r)) return false;
    f.files[mode] = p.string();
  }
  figures->push_back(std::move(f));
  return true;
}

bool LoopFigure(const std::map<std::string, std::vector<LoopCurvePoint>>& curves,
                const std::string& out_dir, std::vector<Figure>* figures, PlotResult* r) {
  bool by_time = true;  // unless a mode's stamps do not advance (then by observation)
  for (const auto& [mode, curve] : curves) by_time = by_time && StampsAdvance(curve);
  const std::string x = by_time ? "1" : "6";
  const auto column = [x](int col) {
    return [x, col](const std::string& c, const std::string& file, const std::string& t) {
      return file + " using " + x + ":" + std::to_string(col) + " with lines lw 2 lc rgb " + c +
             " title " + t;
    };
  };
  // Fixed y ranges (shares): a mode, or a whole run, without closures has no defined
  // point, which gnuplot's autoscale refuses ("all points y value undefined").
  Figure f{"loop_closing",
           by_time ? "robot time [s]" : "observation",
           {{"loop-closure precision, cumulative", false, column(2), "[0:1.05]", ""},
            {"loop-closure recall, cumulative", false, column(3), "[0:1.05]", ""}},
           {},
           {}};
  bool any_accepted = false, any_revisit = false;
  for (const auto& [mode, curve] : curves) {
    const bool accepted = !curve.empty() && curve.back().accepted > 0;
    any_accepted = any_accepted || accepted;
    any_revisit = any_revisit || (!curve.empty() && curve.back().revisits > 0);
    if (!accepted) f.titles[mode] = mode + " (no closures)";
  }
  if (!any_accepted) f.panels[0].note = "no closures";
  if (!any_revisit) f.panels[1].note = "no revisits";
  for (const auto& [mode, curve] : curves) {
    const fs::path p = fs::path(out_dir) / "plot_data" / ("loops_" + SafeName(mode) + ".dat");
    std::ostringstream out;
    out << "# t_s precision recall accepted revisits obs (NaN: not yet defined)\n";
    for (const LoopCurvePoint& q : curve) {
      out << q.t_s << ' ' << (q.accepted > 0 ? std::to_string(q.precision) : "NaN") << ' '
          << (q.revisits > 0 ? std::to_string(q.recall) : "NaN") << ' ' << q.accepted << ' '
          << q.revisits << ' ' << q.obs << '\n';
    }
    if (!WritePlotFile(p, out.str(), r)) return false;
    f.files[mode] = p.string();
  }
  figures->push_back(std::move(f));
  return true;
}

}  // namespace

PlotResult PlotRun(const ModeTimelines& timelines,
                   const std::map<std::string, std::vector<double>>& kl_per_mode,
                   const std::map<std::string, std::vector<LoopCurvePoint>>& curves,
                   const std::string& out_dir, const PlotConfig& config) {
  PlotResult r;
  if (timelines.empty() && kl_per_mode.empty() && curves.empty()) {
    r.error = "nothing to plot";
    return r;
  }
  const std::string terminal = Prepare(out_dir, config, &r);
  if (terminal.empty()) return r;
  std::vector<Figure> figures;
  if ((!timelines.empty() && !TimelineFigures(timelines, out_dir, config, &figures, &r)) ||
      (!kl_per_mode.empty() && !KldFigure(kl_per_mode, out_dir, &figures, &r)) ||
      (!curves.empty() && !LoopFigure(curves, out_dir, &figures, &r))) {
    return r;
  }
  r.ok = RenderAll(figures, out_dir, terminal, config, &r);
  return r;
}

PlotResult PlotTimelines(const ModeTimelines& timelines, const std::string& out_dir,
                         const PlotConfig& config) {
  if (timelines.empty()) return {false, "no timelines to plot", {}, {}, false};
  return PlotRun(timelines, {}, {}, out_dir, config);
}

}  // namespace lifelong::eval
