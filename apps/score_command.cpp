// `lifelong score` (eval/experiment/score.hpp): reads the truth and every system, scores them, and
// writes OUT all or nothing: summary.json (modes[NAME] with a run's fields), report.html and
// trajectories.png.
#include "apps/score_command.hpp"

#include <chrono>
#include <filesystem>
#include <iostream>
#include <set>

#include "apps/exit_codes.hpp"
#include "eval/common/interrupt.hpp"
#include "eval/common/resources.hpp"
#include "eval/common/staged_output.hpp"
#include "eval/experiment/score.hpp"
#include "eval/figures/trajectory_figure.hpp"
#include "eval/metrics/summary.hpp"
#include "eval/report/build_info.hpp"
#include "eval/report/console_table.hpp"
#include "eval/report/report_html.hpp"
#include "io/map_file.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::apps {
namespace {

namespace fs = std::filesystem;

std::vector<eval::ScoredSystem> ReadSystems(const ScoreArgs& a) {
  if (!a.maps.empty() && a.maps.size() != a.trajectories.size()) {
    throw InputError("--map", 0, "",
                     std::to_string(a.maps.size()) + " maps for " +
                         std::to_string(a.trajectories.size()) +
                         " trajectories: give one --map per --trajectory, or none");
  }
  if (!a.names.empty() && a.names.size() != a.trajectories.size()) {
    throw InputError("--name", 0, "",
                     std::to_string(a.names.size()) + " names for " +
                         std::to_string(a.trajectories.size()) + " trajectories");
  }
  std::vector<eval::ScoredSystem> out;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < a.trajectories.size(); ++i) {
    eval::ScoredSystem s;
    s.name = a.names.empty() ? fs::path(a.trajectories[i]).stem().string() : a.names[i];
    if (s.name.empty() || !seen.insert(s.name).second) {
      throw InputError("--name", 0, "",
                       "'" + s.name + "' names two systems (or none): give each a --name");
    }
    s.trajectory = io::ReadTrajectory(a.trajectories[i]);
    if (s.trajectory.empty()) throw InputError(a.trajectories[i], 0, "", "no pose in the file");
    if (!a.maps.empty()) s.map = io::ReadPgmMap(a.maps[i]);
    out.push_back(std::move(s));
  }
  return out;
}

int Score(const ScoreArgs& a) {
  const auto start = std::chrono::steady_clock::now();
  const eval::ScoreTruth truth = eval::LoadScoreTruth(a.truth, a.scenario);
  const std::vector<eval::ScoredSystem> systems = ReadSystems(a);
  eval::StagedOutput staged(a.out);
  eval::RunSummary summary;
  summary.source = a.truth;
  std::vector<eval::AlignedTrack> tracks;
  std::vector<Pose2> reference;
  for (const eval::ScoredSystem& s : systems) {
    eval::ThrowIfInterrupted();
    eval::SystemScore score = eval::ScoreSystem(truth, s);
    std::cerr << s.name << ": " << *score.summary.reference_matched << " of " << s.trajectory.size()
              << " poses paired with the truth (" << truth.kind << ")"
              << (s.map && !truth.walls ? "; no true walls, so the map is not scored" : "") << "\n";
    summary.modes[s.name] = score.summary;
    summary.mode_order.push_back(s.name);
    if (score.truth.size() > reference.size()) reference = score.truth;
    tracks.push_back({s.name, std::move(score.aligned)});
  }
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const fs::path dir = staged.path();
  eval::WriteSummaryJson((dir / "summary.json").string(), summary);
  eval::WriteTrajectoryFigure((dir / "trajectories.png").string(), reference,
                              truth.kind == "corrected log" ? "reference" : "truth", tracks);
  eval::ReportPage page;
  page.title = "lifelong score";
  page.lead_heading = "Trajectories";
  page.summary = summary;
  page.command_line = a.command_line;
  page.working_dir = fs::current_path().string();
  page.build = eval::GetBuildInfo();
  page.lead_figures.push_back(
      {"trajectories.png",
       "Each system's trajectory, aligned to the " + truth.kind + "'s by its ATE alignment.", 0,
       0});
  eval::WriteReportHtml((dir / "report.html").string(), page);
  staged.Commit();
  std::cout << eval::ConsoleTable(summary) << "wrote " << a.out
            << "/summary.json and report.html\n";
  return 0;
}

}  // namespace

int ScoreCommand(const ScoreArgs& a) {
  eval::InstallInterruptHandler();
  return Guarded([&] { return Score(a); },
                 [](const std::exception& e) {
                   return dynamic_cast<const eval::Interrupted*>(&e) != nullptr;
                 });
}

}  // namespace lifelong::apps
