// The banners at the top of report.html: what makes a run's figures doubtful, said before
// any figure is read. A simulation whose robot collided or timed out (red, with the first
// collision's time and object and the simulated against the expected duration; collisions
// the scenario expects are an amber note), a relations replay that used fewer than half
// the relations of its file (red: the relation error describes a small part of the run),
// and the figures gnuplot failed on, each with its log (amber: the rest stands).
#pragma once

#include <string>

#include "eval/report/report_html.hpp"

namespace lifelong::eval {

/// The banners as HTML (<div class="alert"> red, <div class="notice"> amber); "" when
/// there is nothing to say.
std::string ReportAlertsHtml(const ReportPage& page);

}  // namespace lifelong::eval
