// The end-of-run console table; see console_table.hpp.
#include "eval/report/console_table.hpp"

#include "eval/report/report_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <sstream>
#include <vector>

namespace lifelong::eval {
namespace {

using Getter = std::function<std::optional<double>(const ModeSummary&)>;

struct Column {
  const char* header;
  int precision;
  Getter get;
  bool ratio = false;  ///< show mode / baseline instead of the value
};

std::optional<double> Last10(const ModeSummary& m) {
  if (!m.time_per_obs_ms) return std::nullopt;
  return m.time_per_obs_ms->last10_mean;
}
std::optional<double> MeanMs(const ModeSummary& m) {
  if (!m.time_per_obs_ms) return std::nullopt;
  return m.time_per_obs_ms->mean;
}
template <typename T>
std::optional<double> AsDouble(const std::optional<T>& v) {
  if (!v) return std::nullopt;
  return static_cast<double>(*v);
}

std::vector<Column> Columns() {
  return {
      {"obs", 0, [](const ModeSummary& m) { return AsDouble(m.observations); }},
      {"nodes", 0, [](const ModeSummary& m) { return AsDouble(m.nodes_final); }},
      {"edges", 0, [](const ModeSummary& m) { return AsDouble(m.edges_final); }},
      {"kept [%]", 1, [](const ModeSummary& m) { return m.scans_kept_pct; }},
      {"mean [ms/obs]", 2, MeanMs},
      {"last 10 % [ms/obs]", 2, Last10},
      {"wall [s]", 1, [](const ModeSummary& m) { return m.wall_time_s; }},
      {"wall / base", 2, [](const ModeSummary& m) { return m.wall_time_s; }, true},
      {"last 10 % / base", 2, Last10, true},
      {"ATE [m]", 3, [](const ModeSummary& m) { return m.ate_rmse_m; }},
      {"RPE 1 m [m]", 3,
       [](const ModeSummary& m) {
         return m.rpe_1m ? std::optional<double>(m.rpe_1m->trans_rmse_m) : std::nullopt;
       }},
      {"blur [cm]", 2,
       [](const ModeSummary& m) { return m.blur ? m.blur->mean_cm : std::nullopt; }},
      {"rel. [m]", 4,
       [](const ModeSummary& m) {
         return m.relations ? std::optional<double>(m.relations->trans_mean_m) : std::nullopt;
       }},
      {"KL [nats]", 3,
       [](const ModeSummary& m) {
         return m.kld ? std::optional<double>(m.kld->mean) : std::nullopt;
       }},
  };
}

std::string Format(std::optional<double> v, int precision) {
  if (!v || !std::isfinite(*v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", precision, *v);
  return buf;
}

}  // namespace

std::string ConsoleTable(const RunSummary& summary) {
  const std::vector<std::string> order = OrderedModes(summary);
  const std::vector<Column> columns = Columns();
  // Drop columns no mode has a figure for (e.g. ATE in a replay).
  std::vector<const Column*> shown;
  for (const Column& c : columns) {
    const bool any = std::any_of(order.begin(), order.end(), [&](const std::string& n) {
      return c.get(summary.modes.at(n)).has_value();
    });
    if (any && (!c.ratio || order.size() > 1)) shown.push_back(&c);
  }
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> header{"mode"};
  for (const Column* c : shown) header.push_back(c->header);
  rows.push_back(header);
  const ModeSummary* base = order.empty() ? nullptr : &summary.modes.at(order.front());
  for (const std::string& name : order) {
    const ModeSummary& m = summary.modes.at(name);
    std::vector<std::string> row{name + (&m == base && order.size() > 1 ? " (base)" : "")};
    for (const Column* c : shown) {
      std::optional<double> v = c->get(m);
      if (c->ratio) {
        const std::optional<double> b = c->get(*base);
        v = (v && b && *b > 0.0) ? std::optional<double>(*v / *b) : std::nullopt;
      }
      row.push_back(Format(v, c->precision));
    }
    rows.push_back(row);
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
  }
  std::ostringstream out;
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      const std::size_t pad = width[i] - row[i].size();
      if (i == 0) {
        out << row[i] << std::string(pad, ' ');
      } else {
        out << "  " << std::string(pad, ' ') << row[i];
      }
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace lifelong::eval
