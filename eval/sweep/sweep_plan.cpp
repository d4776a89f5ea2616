#include "eval/sweep/sweep_plan.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string ReadText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return "";
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::string SweepPlanToJson(const SweepPlan& plan) {
  json cells = json::array();
  for (const SweepPlanCell& c : plan.cells) {
    json settings = json::object();
    for (const auto& [k, v] : c.settings) settings[k] = v;
    cells.push_back({{"name", c.name},
                     {"source", c.source},
                     {"is_log", c.is_log},
                     {"seed", c.seed ? json(*c.seed) : json(nullptr)},
                     {"settings", settings},
                     {"hash", c.hash},
                     {"argv", c.argv},
                     {"log", c.log}});
  }
  const json j = {{"spec", plan.spec},
                  {"modes", plan.modes},
                  {"baseline", plan.baseline},
                  {"program_id", plan.program_id},
                  {"setting_keys", plan.setting_keys},
                  {"cells", cells}};
  return j.dump(1) + "\n";
}

SweepPlan SweepPlanFromJson(const std::string& text, const std::string& file) {
  SweepPlan plan;
  try {
    const json j = json::parse(text);
    plan.spec = j.at("spec").get<std::string>();
    plan.modes = j.at("modes").get<std::vector<std::string>>();
    plan.baseline = j.at("baseline").get<std::string>();
    plan.program_id = j.value("program_id", std::string());
    plan.setting_keys = j.at("setting_keys").get<std::vector<std::string>>();
    for (const json& c : j.at("cells")) {
      SweepPlanCell cell;
      cell.name = c.at("name").get<std::string>();
      cell.source = c.at("source").get<std::string>();
      cell.is_log = c.at("is_log").get<bool>();
      if (!c.at("seed").is_null()) cell.seed = c.at("seed").get<std::int64_t>();
      // The keys in setting_keys order (a JSON object does not keep the SPEC's).
      for (const std::string& key : plan.setting_keys) {
        cell.settings.emplace_back(key, c.at("settings").at(key).get<std::string>());
      }
      cell.hash = c.at("hash").get<std::string>();
      cell.argv = c.value("argv", std::vector<std::string>{});
      cell.log = c.value("log", std::string());
      plan.cells.push_back(std::move(cell));
    }
  } catch (const json::exception& e) {
    throw InputError(file, 0, "", std::string("not a sweep plan: ") + e.what());
  }
  if (plan.modes.empty()) throw InputError(file, 0, "modes", "no modes");
  return plan;
}

SweepPlan ReadSweepPlan(const std::string& dir) {
  const fs::path p = fs::path(dir) / "sweep.json";
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) {
    throw InputError(p.string(), 0, "", "no sweep here (run `lifelong sweep SPEC -o DIR` first)");
  }
  return SweepPlanFromJson(ReadText(p), p.string());
}

std::string FinishedCellHash(const std::string& cell_dir) {
  const fs::path dir(cell_dir);
  std::error_code ec;
  if (!fs::is_regular_file(dir / "summary.json", ec)) return "";
  const std::string text = ReadText(dir / kCellStampFile);
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!j.is_object() || !j.contains("hash") || !j["hash"].is_string()) return "";
  return j["hash"].get<std::string>();
}

}  // namespace lifelong::eval
