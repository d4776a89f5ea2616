#include "eval/report_alerts.hpp"

#include <sstream>

#include "eval/html.hpp"
#include "eval/report_table.hpp"

namespace lifelong::eval {
namespace {

/// Red when a mode used fewer than half the relations of the file.
std::string RelationsAlert(const ReportPage& page) {
  const RunSummary& s = page.summary;
  if (!s.log || !s.log->relations_in_file) return "";
  const std::int64_t in_file = *s.log->relations_in_file;
  std::string used;
  bool few = false;
  for (const std::string& mode : OrderedModes(s, page.mode_order)) {
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
  return RelationsAlert(page) + FailedFiguresNotice(page);
}

}  // namespace lifelong::eval
