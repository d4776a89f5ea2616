#include "eval/plots.hpp"

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>

#include "io/atomic_file.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

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

struct Figure {
  std::string name;  ///< file stem
  std::string ylabel;
  std::string xlabel;
  bool log_y = false;
  /// One gnuplot plot clause per (mode index, data file, title).
  std::function<std::string(int, const std::string&, const std::string&)> clauses;
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

/// Writes the script, runs gnuplot, renames the PNG into place.
bool Render(const Figure& f, const std::map<std::string, std::string>& data_files,
            const std::string& out_dir, const std::string& terminal, const PlotConfig& c,
            PlotResult* result) {
  const fs::path png = fs::path(out_dir) / (f.name + ".png");
  const std::string tmp = io::TempPathFor(png.string());
  const fs::path script = fs::path(out_dir) / "plot_data" / (f.name + ".gp");
  {
    std::ostringstream gp;
    gp << "set terminal " << terminal << " noenhanced size " << c.width_px << "," << c.height_px
       << "\nset output " << GpQuote(tmp) << "\n"
       << "set xlabel " << GpQuote(f.xlabel) << "\nset ylabel " << GpQuote(f.ylabel) << "\n"
       << "set grid\nset key top left\n"
       << (f.log_y ? "set logscale y\n" : "") << "plot ";
    int i = 0;
    for (const auto& [mode, file] : data_files) {
      gp << (i ? ", \\\n     " : "") << f.clauses(i + 1, GpQuote(file), GpQuote(mode));
      ++i;
    }
    gp << "\n";
    if (!WritePlotFile(script, gp.str(), result)) return false;
  }
  const fs::path log = fs::path(out_dir) / "plot_data" / (f.name + ".log");
  const std::string cmd =
      ShellQuote(c.gnuplot) + " " + ShellQuote(script.string()) + " 2> " + ShellQuote(log.string());
  const int status = std::system(cmd.c_str());
  std::error_code ec;
  if (status != 0 || !fs::exists(tmp)) {
    result->error = "gnuplot failed on " + script.string() + " (see " + log.string() + ")";
    fs::remove(tmp, ec);
    return false;
  }
  try {
    io::CommitTempFile(tmp, png.string());
  } catch (const std::exception& e) {
    result->error = e.what();
    return false;
  }
  result->files.push_back(png.string());
  return true;
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
  return ec ? "" : terminal;
}

std::string Lines(int i, const std::string& file, const std::string& title, int col) {
  return file + " using 1:" + std::to_string(col) + " with lines lw 2 lc " + std::to_string(i) +
         " title " + title;
}

}  // namespace

bool GnuplotAvailable(const std::string& gnuplot, std::string* terminal) {
  const std::string cmd = ShellQuote(gnuplot) + " -e 'set terminal' 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return false;
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof(buf), pipe)) out += buf;
  const int status = pclose(pipe);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return false;
  if (out.find("png") == std::string::npos) return false;
  if (terminal) *terminal = out.find("pngcairo") != std::string::npos ? "pngcairo" : "png";
  return true;
}

PlotResult PlotTimelines(const ModeTimelines& timelines, const std::string& out_dir,
                         const PlotConfig& config) {
  PlotResult r;
  if (timelines.empty()) {
    r.error = "no timelines to plot";
    return r;
  }
  const std::string terminal = Prepare(out_dir, config, &r);
  if (terminal.empty()) return r;
  std::map<std::string, std::string> files;  // mode -> data file
  for (const auto& [mode, rows] : timelines) {
    std::vector<double> ms;
    for (const TimelineRow& row : rows) ms.push_back(row.time_ms);
    const std::vector<double> ma = MovingAverage(ms, config.moving_average);
    const fs::path p = fs::path(out_dir) / "plot_data" / ("timeline_" + SafeName(mode) + ".dat");
    std::ostringstream out;
    out << "# obs time_ms time_ms_moving_average nodes edges gamma\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      out << rows[i].obs << ' ' << rows[i].time_ms << ' ' << ma[i] << ' ' << rows[i].nodes << ' '
          << rows[i].edges << ' ' << rows[i].gamma << '\n';
    }
    if (!WritePlotFile(p, out.str(), &r)) return r;
    files[mode] = p.string();
  }
  const std::string ma_label = std::to_string(config.moving_average);
  const std::vector<Figure> figures = {
      {"time_per_obs", "time per observation [ms] (lines: moving average of " + ma_label + ")",
       "observation", config.log_time,
       [](int i, const std::string& f, const std::string& t) {
         return f + " using 1:2 with dots lc " + std::to_string(i) + " notitle, " +
                Lines(i, f, t, 3);
       }},
      {"nodes", "nodes", "observation", false,
       [](int i, const std::string& f, const std::string& t) { return Lines(i, f, t, 4); }},
      {"edges", "edges", "observation", false,
       [](int i, const std::string& f, const std::string& t) { return Lines(i, f, t, 5); }},
      {"gamma", "gamma index e / (v (v-1) / 2)", "observation", true,
       [](int i, const std::string& f, const std::string& t) { return Lines(i, f, t, 6); }},
  };
  r.ok = true;
  for (const Figure& f : figures) r.ok = Render(f, files, out_dir, terminal, config, &r) && r.ok;
  return r;
}

PlotResult PlotKld(const std::map<std::string, std::vector<double>>& kl_per_mode,
                   const std::string& out_dir, const PlotConfig& config) {
  PlotResult r;
  if (kl_per_mode.empty()) {
    r.error = "no KL divergences to plot";
    return r;
  }
  const std::string terminal = Prepare(out_dir, config, &r);
  if (terminal.empty()) return r;
  std::map<std::string, std::string> files;
  for (const auto& [mode, kl] : kl_per_mode) {
    const fs::path p = fs::path(out_dir) / "plot_data" / ("kld_" + SafeName(mode) + ".dat");
    std::ostringstream out;
    out << "# marginalization kl_divergence\n";
    for (std::size_t i = 0; i < kl.size(); ++i) out << i << ' ' << kl[i] << '\n';
    if (!WritePlotFile(p, out.str(), &r)) return r;
    files[mode] = p.string();
  }
  const Figure f{"kld", "KL divergence of the approximate clique [nats]", "marginalization", false,
                 [](int i, const std::string& file, const std::string& t) {
                   return file + " using 1:2 with points pt 7 ps 0.5 lc " + std::to_string(i) +
                          " title " + t;
                 }};
  r.ok = Render(f, files, out_dir, terminal, config, &r);
  return r;
}

}  // namespace lifelong::eval
