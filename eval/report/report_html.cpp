#include "eval/report/report_html.hpp"
#include "io/atomic_file.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "eval/common/html.hpp"
#include "eval/common/resources.hpp"
#include "eval/figures/mode_colors.hpp"
#include "eval/report/report_alerts.hpp"
#include "eval/report/report_table.hpp"
#include "render/palette.hpp"

namespace lifelong::eval {
namespace {

const char kCss[] =
    "body{font-family:sans-serif;margin:1em auto;max-width:1400px;padding:0 1em;color:#222;"
    "line-height:1.35}h1{margin:0 0 .1em}h2{border-bottom:1px solid #ddd;padding-bottom:.1em;"
    "margin:1em 0 .4em;font-size:1.3em}nav a{margin-right:1em}.lead{color:#555;margin:0}"
    "table{border-collapse:collapse;font-size:90%}td,th{border:1px solid #ccc;padding:1px 8px}"
    "table.summary td{text-align:right}table.summary td:first-child,table.summary td.unit,"
    "table.summary "
    "td.def{text-align:left}td.def{color:#555;font-size:92%}td.unit{color:#555}td.na{color:#999;"
    "text-align:center;font-style:italic}td.warn{background:#fde2e1;color:#900}"
    "tr.group th{background:#eef2f6;text-align:left}.ratio{color:#888;"
    "font-size:85%}.swatch{display:inline-block;width:.9em;height:.9em;margin-right:.35em;"
    "vertical-align:-.1em;border-radius:2px}.note{color:#555;font-size:90%;margin:.3em 0}"
    ".row{display:flex;flex-wrap:wrap;gap:1em;align-items:flex-start}"
    "figure{margin:0}figcaption{font-size:85%;color:#444;margin-top:.1em;line-height:1.25}"
    ".lead-plots figure{width:440px}.lead-plots img{width:440px;border:1px solid #ddd}"
    ".plots figure{width:326px}.plots img{width:326px;border:1px solid #ddd}"
    ".maps{display:grid;gap:16px;align-items:start}.card h3{font-size:100%;margin:0 0 .2em}"
    ".card figure{margin-bottom:.3em}.card img{border:1px solid #ccc}"
    ".legend{font-size:90%;margin:.3em 0}.legend span.item{margin-right:1.2em;white-space:nowrap}"
    ".line{display:inline-block;width:2em;height:3px;vertical-align:middle;margin-right:.4em}"
    ".dot{display:inline-block;width:7px;height:7px;border-radius:50%;margin:0 .5em 0 .3em}"
    ".alert{border:2px solid #c00;background:#fde2e1;color:#700;padding:.5em .8em;margin:.5em 0;"
    "border-radius:4px;font-size:110%}.alert b{color:#a00}.notice{border:1px solid "
    "#cb8;background:#fff6e0;"
    "padding:.4em .8em;margin:.5em 0;border-radius:4px}"
    "details{margin:.6em 0}details summary{cursor:pointer;color:#246}"
    "code{background:#f3f3f3;padding:1px 3px}dl.prov{display:grid;grid-template-columns:"
    "max-content auto;gap:.1em 1em;font-size:90%}dl.prov dt{font-weight:bold}dl.prov dd{margin:0}"
    "ul.files{list-style:none;padding:0;font-size:90%}ul.files li{margin:.1em 0}"
    "ul.files a{margin-right:.8em}";

std::string Hex(const render::Rgb& c) { return HexColour(c); }

std::string Figure(const ReportFigure& f) {
  std::ostringstream h;
  const std::string src = HtmlEscape(f.path);
  h << "<figure><a href=\"" << src << "\"><img src=\"" << src << "\" alt=\""
    << HtmlEscape(f.caption) << "\"";
  if (f.width_px > 0 && f.height_px > 0) {
    h << " width=\"" << f.width_px << "\" height=\"" << f.height_px << "\"";
  }
  h << "></a><figcaption>" << HtmlEscape(f.caption) << "</figcaption></figure>\n";
  return h.str();
}

std::string Figures(const std::vector<ReportFigure>& figures) {
  std::string html;
  for (const ReportFigure& f : figures) html += Figure(f);
  return html;
}

std::string LegendItem(const render::Rgb& c, const std::string& label, const char* cls) {
  return "<span class=\"item\"><span class=\"" + std::string(cls) +
         "\" style=\"background:" + Hex(c) + "\"></span>" + label + "</span>";
}

/// The colours of render/palette.hpp, as drawn in the maps and graphs, on one line.
std::string Legend(const ReportPage& page) {
  bool prior = false;
  for (const auto& [name, mode] : page.summary.modes)
    prior = prior || mode.edges_by_kind.count("prior");
  std::string html = "<div class=\"legend\">";
  html += LegendItem(render::EdgeColour(EdgeKind::kOdometry), "odometry edge", "line");
  html += LegendItem(render::EdgeColour(EdgeKind::kLoop), "loop closure (thick, on top)", "line");
  html += LegendItem(render::EdgeColour(EdgeKind::kMarginal),
                     "marginal edge (from removed nodes: Chow-Liu tree or naive; an exact "
                     "clique from its first node to each other)",
                     "line");
  if (prior) html += LegendItem(render::EdgeColour(EdgeKind::kPrior), "prior", "line");
  html += LegendItem(render::kGraphNode, "graph node", "dot");
  if (page.true_path_in_maps) {
    html += LegendItem(render::kTrueTrajectory, "true trajectory (thin, under the graph)", "line");
  }
  return html + "</div>\n";
}

/// The maps' grid: one card per mode (its map, then its graph alone), the truth's first.
std::string MapGrid(const ReportPage& page) {
  std::ostringstream h;
  h << "<div class=\"maps\" style=\"grid-template-columns:repeat(" << std::max(page.map_columns, 1)
    << ",max-content)\">\n";
  for (const ReportMapCard& card : page.map_cards) {
    h << "<div class=\"card\"><h3>";
    if (!card.colour.empty()) {
      h << "<span class=\"swatch\" style=\"background:" << card.colour << "\"></span>";
    }
    h << HtmlEscape(card.name) << "</h3>\n" << Figures(card.figures) << "</div>\n";
  }
  return h.str() + "</div>\n";
}

std::string Num(double v, const char* fmt = "%.3g") {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

/// "mean ± std"; published figures keep their digits ("%g"), ours get three.
std::string PlusMinus(double mean, double std, const char* fmt = "%.3g") {
  return Num(mean, fmt) + " &plusmn; " + Num(std, fmt);
}

/// Published relation errors next to this run's, and the other published notes.
std::string Reference(const ReportPage& page) {
  if (!page.reference) return "";
  const ReferenceFigures& r = *page.reference;
  std::ostringstream h;
  h << "<h2 id=\"published\">Published figures: " << HtmlEscape(r.dataset) << "</h2>\n";
  if (!r.relation_errors.empty()) {
    h << "<table><tr><th>method</th><th>translation [m]</th><th>rotation [deg]</th>"
         "<th>relations</th><th>source</th></tr>\n";
    for (const PublishedRelationError& e : r.relation_errors) {
      h << "<tr><td>" << HtmlEscape(e.method) << "</td><td>"
        << PlusMinus(e.trans_mean_m, e.trans_std_m, "%g") << "</td><td>"
        << (e.rot_mean_deg ? PlusMinus(*e.rot_mean_deg, e.rot_std_deg.value_or(0.0), "%g")
                           : "&ndash;")
        << "</td><td>whole log</td><td>" << HtmlEscape(e.citation) << "</td></tr>\n";
    }
    for (const std::string& m : OrderedModes(page.summary)) {
      const auto& rel = page.summary.modes.at(m).relations;
      if (!rel) continue;
      h << "<tr><td><span class=\"swatch\" style=\"background:" << ModeColourHex(m)
        << "\"></span><b>" << HtmlEscape(m) << "</b> (this run)</td><td>"
        << PlusMinus(rel->trans_mean_m, rel->trans_std_m) << "</td><td>"
        << PlusMinus(rel->rot_mean_deg, rel->rot_std_deg) << "</td><td>" << rel->count
        << "</td><td>this report</td></tr>\n";
    }
    h << "</table>\n<p class=\"note\">Mean &plusmn; standard deviation of the relation error "
         "(Kümmerle et al. 2009); "
      << HtmlEscape(r.scope) << ".</p>\n";
  }
  if (!r.notes.empty()) {
    h << "<ul>\n";
    for (const std::string& n : r.notes) h << "<li>" << HtmlEscape(n) << "</li>\n";
    h << "</ul>\n";
  }
  return h.str();
}

std::string Files(const ReportPage& page) {
  std::ostringstream h;
  h << "<h2 id=\"files\">Files</h2>\n<ul class=\"files\">\n";
  for (const ReportLinkGroup& g : page.files) {
    h << "<li><b>" << HtmlEscape(g.name) << "</b>: ";
    for (const ReportLink& l : g.links) {
      h << "<a href=\"" << HtmlEscape(l.path) << "\">" << HtmlEscape(l.label) << "</a>";
    }
    h << "</li>\n";
  }
  return h.str() + "</ul>\n";
}

std::string Provenance(const ReportPage& page) {
  const std::string machine = page.machine.empty() ? CpuModelName() : page.machine;
  std::ostringstream h;
  h << "<h2 id=\"provenance\">Provenance</h2>\n<dl class=\"prov\">\n"
    << "<dt>program</dt><dd>lifelong " << HtmlEscape(page.build.version) << "</dd>\n"
    << "<dt>commit</dt><dd><code>" << HtmlEscape(page.build.commit) << "</code></dd>\n"
    << "<dt>command</dt><dd><code>" << HtmlEscape(page.command_line) << "</code></dd>\n";
  if (!page.working_dir.empty()) {
    h << "<dt>run in</dt><dd><code>" << HtmlEscape(page.working_dir) << "</code></dd>\n";
  }
  h << "<dt>machine</dt><dd>" << HtmlEscape(machine) << "</dd>\n";
  if (!page.written_utc.empty()) {
    h << "<dt>written</dt><dd>" << HtmlEscape(page.written_utc) << "</dd>\n";
  }
  return h.str() + "</dl>\n";
}

std::string Header(const ReportPage& page) {
  const RunSummary& s = page.summary;
  std::ostringstream h;
  h << "<h1>" << HtmlEscape(page.title) << "</h1>\n<p class=\"lead\">source <code>"
    << HtmlEscape(s.source) << "</code>";
  if (s.seed) h << ", seed " << *s.seed;
  if (s.log_duration_s) h << ", " << Num(*s.log_duration_s, "%.0f") << " s of data";
  h << ", " << Num(s.wall_time_s, "%.1f") << " s wall time; modes ";
  const std::vector<std::string> modes = OrderedModes(s);
  for (std::size_t i = 0; i < modes.size(); ++i) {
    h << (i ? ", " : "") << "<span class=\"swatch\" style=\"background:" << ModeColourHex(modes[i])
      << "\"></span>" << HtmlEscape(modes[i]);
  }
  // Links to the sections the page has.
  h << "</p>\n<nav><a href=\"#plots\">"
    << HtmlEscape(page.lead_heading.substr(0, page.lead_heading.find(' '))) << "</a>";
  if (!page.map_cards.empty() || !page.maps.empty()) h << "<a href=\"#maps\">Maps</a>";
  h << "<a href=\"#summary\">Key figures</a>";
  if (page.reference) h << "<a href=\"#published\">Published figures</a>";
  if (!page.figures.empty()) h << "<a href=\"#more\">More plots</a>";
  if (!page.files.empty()) h << "<a href=\"#files\">Files</a>";
  h << "<a href=\"#provenance\">Provenance</a></nav>\n";
  return h.str();
}

}  // namespace

/// Laid out for a reader of the seed's chapter 6: the charts and maps first, then the key
/// figures (the full table folded), then the rest.
std::string ReportHtmlText(const ReportPage& page) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>"
    << HtmlEscape(page.title) << "</title>\n<style>" << kCss << "</style></head><body>\n"
    << Header(page) << ReportAlertsHtml(page);
  h << "<h2 id=\"plots\">" << HtmlEscape(page.lead_heading) << "</h2>\n";
  if (!page.figures_note.empty()) {
    h << "<div class=\"notice\">" << HtmlEscape(page.figures_note) << "</div>\n";
  }
  h << "<div class=\"row lead-plots\">\n" << Figures(page.lead_figures) << "</div>\n";
  if (!page.map_cards.empty() || !page.maps.empty()) {
    h << "<h2 id=\"maps\">Maps and graphs</h2>\n" << Legend(page) << MapGrid(page);
  }
  if (!page.maps_note.empty()) h << "<p class=\"note\">" << HtmlEscape(page.maps_note) << "</p>\n";
  if (!page.change_strips.empty()) {
    h << "<h2 id=\"changes\">Doors and boxes that changed</h2>\n<p class=\"note\">Each mode's "
         "map around each changed object, in the truth's frame: its outline at the end in "
         "green, its earlier outlines in red. A map that follows the building is black under "
         "the green and white under the red.</p>\n"
      << Figures(page.change_strips);
  }
  h << "<h2 id=\"summary\">Key figures</h2>\n"
    << KeyTableHtml(page.summary)
    << "<details><summary>All figures, with their definitions</summary>\n"
    << SummaryTableHtml(page.summary) << "</details>\n"
    << Reference(page);
  if (!page.figures.empty()) {
    h << "<h2 id=\"more\">More plots</h2>\n<div class=\"row plots\">\n"
      << Figures(page.figures) << "</div>\n";
  }
  if (!page.files.empty()) h << Files(page);
  h << Provenance(page) << "</body></html>\n";
  return h.str();
}

void WriteReportHtml(const std::string& path, const ReportPage& page) {
  io::WriteFileAtomically(path, ReportHtmlText(page));
}

}  // namespace lifelong::eval
