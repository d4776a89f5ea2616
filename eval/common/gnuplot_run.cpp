#include "eval/common/gnuplot_run.hpp"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "io/atomic_file.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

fs::path TmpPng(const std::string& out_dir, const std::string& name) {
  return io::TempPathFor((fs::path(out_dir) / (name + ".png")).string());
}

/// Runs gnuplot on the scripts of `names` from out_dir, stderr to plot_data/<log>; true
/// when it exited 0.
bool Run(const std::string& gnuplot, const std::string& out_dir,
         const std::vector<std::string>& names, const std::string& log) {
  std::string cmd = "cd " + ShellQuote(out_dir) + " && " + ShellQuote(gnuplot);
  for (const std::string& name : names) cmd += " " + ShellQuote("plot_data/" + name + ".gp");
  cmd += " 2> " + ShellQuote("plot_data/" + log);
  return std::system(cmd.c_str()) == 0;
}

}  // namespace

std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

GnuplotRun RunGnuplotScripts(const std::string& gnuplot, const std::string& out_dir,
                             const std::vector<std::string>& names) {
  GnuplotRun run;
  if (names.empty()) return run;
  std::error_code ec;
  const fs::path plot_data = fs::path(out_dir) / "plot_data";
  for (const std::string& name : names) fs::remove(plot_data / (name + ".log"), ec);
  if (Run(gnuplot, out_dir, names, "gnuplot.log")) {
    for (const std::string& name : names) {
      // A script that exits 0 without drawing (a stand-in binary) is a failure too.
      (fs::exists(TmpPng(out_dir, name)) ? run.drawn : run.failed).push_back(name);
    }
    if (run.failed.empty()) return run;
    run = {};
  }
  // Some script failed and gnuplot stopped there: each figure again, alone.
  for (const std::string& name : names) {
    fs::remove(TmpPng(out_dir, name), ec);
    const bool ok = Run(gnuplot, out_dir, {name}, name + ".log");
    if (ok && fs::exists(TmpPng(out_dir, name))) {
      fs::remove(plot_data / (name + ".log"), ec);
      run.drawn.push_back(name);
    } else {
      run.failed.push_back(name);
    }
  }
  // A failing script may have drawn another's file: no temporary of a lost figure is left.
  for (const std::string& name : run.failed) fs::remove(TmpPng(out_dir, name), ec);
  return run;
}

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

}  // namespace lifelong::eval
