// The sweep SPEC: every kind of bad input is an InputError naming the file, line and
// field; a good SPEC expands into the expected cells with generated inputs.
#include "eval/sweep/sweep_spec.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "eval/experiment/mapper_config_file.hpp"
#include "eval/sweep/sweep_cells.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

const std::string kSource = LIFELONG_SOURCE_DIR;

// A SPEC in a temporary folder beside which scenarios/corridor_3.yaml is reachable.
std::string WriteSpec(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(::testing::TempDir()) / "sweep_spec_test";
  fs::create_directories(dir);
  const fs::path p = dir / (name + ".yaml");
  std::ofstream(p) << text;
  return p.string();
}

const std::string kScenario = "scenarios: [" + kSource + "/scenarios/corridor_3.yaml]\n";

// Loads `text` and expects an InputError at `line` for `field`.
void ExpectError(const std::string& name, const std::string& text, int line,
                 const std::string& field, const std::string& words) {
  const std::string path = WriteSpec(name, text);
  try {
    LoadSweepSpec(path);
    ADD_FAILURE() << name << ": no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path) << name;
    EXPECT_EQ(e.line(), line) << name << ": " << e.what();
    EXPECT_EQ(e.field(), field) << name << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << name << ": " << e.what();
  }
}

TEST(SweepSpec, EachKindOfBadInputNamesFileLineAndField) {
  ExpectError("unknown_key", kScenario + "modes: [standard]\nrepeats: 3\n", 3, "repeats",
              "unknown key");
  ExpectError("empty_seeds", kScenario + "seeds: []\nmodes: [standard]\n", 2, "seeds", "empty");
  ExpectError("empty_modes", kScenario + "modes: []\n", 2, "modes", "empty");
  ExpectError("empty_scenarios", "scenarios: []\nmodes: [standard]\n", 1, "scenarios", "empty");
  ExpectError("missing_scenario", "modes: [standard]\nscenarios: [nowhere.yaml]\n", 2,
              "scenarios[0]", "no such scenario");
  ExpectError("missing_log", kScenario + "modes: [standard]\nlogs:\n  - {log: no.clf}\n", 4,
              "logs[0].log", "no such log");
  ExpectError("log_key", kScenario + "modes: [standard]\nlogs:\n  - {log: a.clf, offset: 1}\n", 4,
              "logs[0].offset", "unknown key");
  // A NaN offset failed each cell at run time; it is refused with the spec.
  ExpectError("nan_offset",
              kScenario + "modes: [standard]\nlogs:\n  - {log: a.clf, relations_offset_s: .nan}\n",
              4, "logs[0].relations_offset_s", "finite number");
  ExpectError("unknown_mode", kScenario + "modes:\n  - standard\n  - prunned\n", 4, "modes[1]",
              "unknown mode 'prunned'");
  ExpectError("unknown_setting",
              kScenario + "modes: [standard]\nsettings:\n  pruning.gain_bits: [0, 5]\n", 4,
              "settings.pruning.gain_bits", "unknown key");
  ExpectError("bad_value", kScenario + "modes: [standard]\nsettings:\n  grid.resolution_m: [-1]\n",
              4, "settings.grid.resolution_m", "must be in [0.005, 10] m");
  ExpectError("empty_setting",
              kScenario + "modes: [standard]\nsettings:\n  grid.resolution_m: []\n", 4,
              "settings.grid.resolution_m", "empty");
  ExpectError("baseline", kScenario + "modes: [standard]\nbaseline: pruned\n", 3, "baseline",
              "not one of the modes");
  ExpectError("no_source", "modes: [standard]\n", 1, "scenarios", "neither scenarios nor logs");
  ExpectError("no_modes", kScenario, 1, "modes", "missing");
  ExpectError("seed", kScenario + "modes: [standard]\nseeds: [1, x]\n", 3, "seeds[1]", "integer");
  ExpectError("seeded", kScenario + "modes: [standard]\nlogs:\n  - {log: a.clf, seeded: often}\n",
              4, "logs[0].seeded", "true or false");
}

// A log is replayed once, as recorded; a seeded one once per seed, as draws (replay --seed).
TEST(SweepSpec, ASeededLogIsReplayedAsOneDrawPerSeed) {
  const fs::path log = fs::path(::testing::TempDir()) / "sweep_spec_test" / "fhw-corrected.log.gz";
  fs::create_directories(log.parent_path());
  std::ofstream(log) << "not read while planning\n";
  const std::string path = WriteSpec("seeded", "logs:\n  - {log: " + log.string() +
                                                   ", seeded: true}\n  - {log: " + log.string() +
                                                   "}\nseeds: [3, 4]\nmodes: [standard]\n");
  const SweepSpec spec = LoadSweepSpec(path);
  ASSERT_EQ(spec.sources.size(), 2u);
  EXPECT_TRUE(spec.sources[0].seeded);
  EXPECT_FALSE(spec.sources[1].seeded);
  const SweepPlan plan = ExpandSweep(spec, "test");
  ASSERT_EQ(plan.cells.size(), 3u);
  EXPECT_EQ(plan.cells[0].name, "fhw-corrected-seed3");
  EXPECT_EQ(plan.cells[1].name, "fhw-corrected-seed4");
  EXPECT_EQ(plan.cells[2].name, "fhw-corrected");
  EXPECT_NE(plan.cells[0].hash, plan.cells[1].hash);
  const auto argv = CellCommand("/bin/lifelong", spec, plan.cells[1], "", "/in/c.yaml", "/o");
  const auto seed = std::find(argv.begin(), argv.end(), "--seed");
  ASSERT_NE(seed, argv.end());
  EXPECT_EQ(*(seed + 1), "4");
  const auto once = CellCommand("/bin/lifelong", spec, plan.cells[2], "", "/in/c.yaml", "/o");
  EXPECT_EQ(std::count(once.begin(), once.end(), "--seed"), 0);
}

TEST(SweepSpec, ASettingCombinationIsCheckedAsAWhole) {
  // Each value alone is fine (defaults 0.3 and 2.0); min_window_m 1.5 with max 1 is not.
  const std::string path = WriteSpec(
      "combination", kScenario +
                         "modes: [standard]\nsettings:\n  loops.min_window_m: [0.5, 1.5]\n"
                         "  loops.max_window_m: [1, 3]\n");
  const SweepSpec spec = LoadSweepSpec(path);
  try {
    ExpandSweep(spec, "test");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find("min_window_m=1.5-max_window_m=1:"), std::string::npos)
        << e.what();
  }
}

TEST(SweepSpec, ExpandsScenariosSeedsAndSettingsIntoNamedCells) {
  const std::string path = WriteSpec(
      "good", kScenario +
                  "seeds: [1, 2]\nmodes: [standard, pruned]\nbaseline: pruned\n"
                  "settings:\n  pruning.gain_threshold_bits: [0, 5]\n  optimizer.method: [gn]\n");
  const SweepSpec spec = LoadSweepSpec(path);
  EXPECT_EQ(spec.modes, (std::vector<std::string>{"pruned", "standard"}));  // baseline first
  const SweepPlan plan = ExpandSweep(spec, "test 1");
  ASSERT_EQ(plan.cells.size(), 4u);
  EXPECT_EQ(plan.cells[0].name, "corridor_3-seed1-gain_threshold_bits=0-method=gn");
  EXPECT_EQ(plan.cells[3].name, "corridor_3-seed2-gain_threshold_bits=5-method=gn");
  // Different inputs, different hashes; the same inputs, the same hash.
  EXPECT_NE(plan.cells[0].hash, plan.cells[1].hash);
  EXPECT_EQ(ExpandSweep(spec, "test 1").cells[2].hash, plan.cells[2].hash);
  EXPECT_NE(ExpandSweep(spec, "test 2").cells[2].hash, plan.cells[2].hash);

  const CellInputs in = MakeCellInputs(spec, plan.cells[3]);
  const slam::MapperConfig config = LoadMapperConfigFromString(in.config_yaml, "generated");
  EXPECT_EQ(config.pruning.gain_threshold_bits, 5.0);
  EXPECT_EQ(config.optimizer.method, slam::OptimizerMethod::kGaussNewton);
  const YAML::Node scenario = YAML::Load(in.scenario_yaml);
  EXPECT_EQ(scenario["seed"].as<int>(), 2);
  EXPECT_EQ(scenario["world"].as<std::string>(), kSource + "/worlds/corridor.yaml");
  EXPECT_EQ(scenario["name"].as<std::string>(), "corridor_3");

  const auto argv =
      CellCommand("/bin/lifelong", spec, plan.cells[0], "/in/s.yaml", "/in/c.yaml", "/out/cell");
  EXPECT_EQ(argv,
            (std::vector<std::string>{"/bin/lifelong", "run", "/in/s.yaml", "-o", "/out/cell",
                                      "--modes", "pruned,standard", "--config", "/in/c.yaml"}));
}

TEST(SweepSpec, SettingsBecomeNestedYaml) {
  EXPECT_EQ(MapperSettingsYaml({}), "{}\n");
  const std::vector<std::pair<std::string, std::string>> settings = {
      {"loops.verify.min_group", "4"}, {"loops.enabled", "false"}};
  const std::string yaml = MapperSettingsYaml(settings);
  const YAML::Node n = YAML::Load(yaml);
  EXPECT_EQ(n["loops"]["verify"]["min_group"].as<int>(), 4);
  EXPECT_EQ(n["loops"]["enabled"].as<bool>(), false);
  // Applied directly, the settings give what the cell's file gives.
  const slam::MapperConfig direct = ApplyMapperSettings(settings, "settings");
  const slam::MapperConfig from_file = LoadMapperConfigFromString(yaml, "cell.yaml");
  EXPECT_EQ(direct.loops.verify.min_group, 4);
  EXPECT_FALSE(direct.loops.enabled);
  EXPECT_EQ(MapperConfigToYaml(direct), MapperConfigToYaml(from_file));
}

// A setting is checked where it is applied: a value out of range or an unknown key is an
// InputError naming the dotted key.
TEST(SweepSpec, AppliedSettingsAreCheckedByTheReader) {
  try {
    ApplyMapperSettings({{"pruning.radius_m", "-1"}}, "setting");
    FAIL() << "a negative radius was applied";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pruning.radius_m"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ApplyMapperSettings({{"pruning.no_such_key", "1"}}, "setting"), InputError);
}

// Every SPEC shipped in sweeps/ must load (its scenarios, logs and setting keys exist and
// check out), so that a README or docs/results.md command never meets a broken SPEC.
TEST(SweepSpec, EveryShippedSpecLoads) {
  int specs = 0;
  for (const auto& entry : fs::directory_iterator(kSource + "/sweeps")) {
    if (entry.path().extension() != ".yaml") continue;
    ++specs;
    SCOPED_TRACE(entry.path().string());
    const SweepSpec spec = LoadSweepSpec(entry.path().string());
    EXPECT_FALSE(spec.sources.empty());
    EXPECT_FALSE(spec.modes.empty());
    for (const SweepSource& source : spec.sources) EXPECT_TRUE(fs::exists(source.path));
  }
  EXPECT_GE(specs, 9);
}

}  // namespace
}  // namespace lifelong::eval
