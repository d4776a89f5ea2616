#include "eval/report/report_alerts.hpp"

#include <cstdio>
#include <sstream>

#include "eval/common/html.hpp"
#include "eval/report/report_table.hpp"

namespace lifelong::eval {
namespace {

std::string Seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f s", s);
  return buf;
}

/// "the first at 12.3 s, with door lab_a": when and what the robot hit first.
std::string FirstCollision(const SimulationOutcome& o) {
  std::string text;
  if (o.first_collision_s) text += "the first at " + Seconds(*o.first_collision_s);
  if (o.first_collision_with) {
    text += (text.empty() ? "the first " : ", ") + std::string("with <b>") +
            HtmlEscape(*o.first_collision_with) + "</b>";
  }
  return text;
}

/// Red when the simulated robot collided (unless the scenario expects it) or timed out:
/// the run did not follow its route, and every figure below describes another run.
/// Expected collisions are a note.
std::string SimulationAlert(const RunSummary& s) {
  if (!s.simulation) return "";
  const SimulationOutcome& o = *s.simulation;
  const std::string count =
      std::to_string(o.collisions) + (o.collisions == 1 ? " collision" : " collisions");
  const std::string first = FirstCollision(o);
  const std::string duration =
      "simulated " + Seconds(o.duration_s) + " of the expected " + Seconds(o.expected_duration_s);
  if (o.Failed()) {
    std::string what;
    if (o.collided && !o.collisions_expected) {
      what = "the robot collided (" + count + (first.empty() ? "" : "; " + first) + ")";
    }
    if (o.timed_out) what += (what.empty() ? "" : ", and ") + std::string("the route timed out");
    return "<div class=\"alert\"><b>The simulation failed:</b> " + what + "; " + duration +
           ". The robot did not drive the scenario's route: the figures below describe "
           "another run.</div>\n";
  }
  if (o.collided) {
    return "<div class=\"notice\">Collisions the scenario expects (collisions_expected): " + count +
           (first.empty() ? "" : ", " + first) + "; " + duration + ".</div>\n";
  }
  return "";
}

/// Red when a mode used fewer than half the relations of the file.
std::string RelationsAlert(const ReportPage& page) {
  const RunSummary& s = page.summary;
  if (!s.log || !s.log->relations_in_file) return "";
  const std::int64_t in_file = *s.log->relations_in_file;
  std::string used;
  bool few = false;
  for (const std::string& mode : OrderedModes(s)) {
    const auto& rel = s.modes.at(mode).relations;
    if (!rel) continue;
    few = few || rel->count * 2 < in_file;
    used += (used.empty() ? "" : ", ") + HtmlEscape(mode) + " " + std::to_string(rel->count);
  }
  if (!few) return "";
  return "<div class=\"alert\"><b>Few relations used.</b> Of the " + std::to_string(in_file) +
         " relations in the file, fewer than half fell on scans of the log (" + used +
         "): the relation error describes only part of the run. Check the relations file and "
         "<code>--relations-offset</code>.</div>\n";
}

/// Amber: each figure gnuplot failed on, with its log.
std::string FailedFiguresNotice(const ReportPage& page) {
  if (page.failed_figures.empty()) return "";
  std::ostringstream h;
  h << "<div class=\"notice\"><b>Figures not drawn:</b> ";
  for (std::size_t i = 0; i < page.failed_figures.size(); ++i) {
    const ReportLink& f = page.failed_figures[i];
    h << (i ? "; " : "") << HtmlEscape(f.label) << " (gnuplot failed, see <a href=\""
      << HtmlEscape(f.path) << "\">" << HtmlEscape(f.path) << "</a>)";
  }
  h << ". The other figures are complete.</div>\n";
  return h.str();
}

}  // namespace

std::string ReportAlertsHtml(const ReportPage& page) {
  return SimulationAlert(page.summary) + RelationsAlert(page) + FailedFiguresNotice(page);
}

}  // namespace lifelong::eval
