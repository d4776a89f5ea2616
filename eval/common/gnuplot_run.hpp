// Runs the gnuplot scripts of a run's figures so that one figure's failure costs only that
// figure. All scripts run in one gnuplot process first (a process per figure cost about
// 50 ms each); gnuplot stops at the first script that fails, so then every script runs
// again in a process of its own, and only the figures whose own script failed are lost.
#pragma once

#include <string>
#include <vector>

namespace lifelong::eval {

struct GnuplotRun {
  std::vector<std::string> drawn;   ///< names whose <name>.tmp.png was drawn
  std::vector<std::string> failed;  ///< names whose script failed (no <name>.tmp.png left)
};

/// Runs plot_data/<name>.gp (drawing <name>.tmp.png) for each name, from out_dir: paths in
/// the scripts are relative to it. gnuplot's messages go to plot_data/gnuplot.log, and
/// for each failed figure to plot_data/<name>.log: that file exists exactly when the
/// figure failed (a figure that drew leaves none, and an old one is removed first).
GnuplotRun RunGnuplotScripts(const std::string& gnuplot, const std::string& out_dir,
                             const std::vector<std::string>& names);

/// True when `gnuplot` runs; fills *terminal with "pngcairo" or "png" when given.
bool GnuplotAvailable(const std::string& gnuplot, std::string* terminal = nullptr);

/// `s` quoted for /bin/sh.
std::string ShellQuote(const std::string& s);

}  // namespace lifelong::eval
