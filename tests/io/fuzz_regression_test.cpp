// Regression inputs found by the fuzzers (fuzz/) and by review: every file under
// tests/data/fuzz_regressions/<target>/ must load or throw lifelong::InputError; a crash,
// a sanitizer report, a huge allocation or any other exception type fails the test.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz/map_input.hpp"
#include "io/carmen_log.hpp"
#include "io/graph_file.hpp"
#include "io/map_file.hpp"
#include "io/relations.hpp"
#include "io/tum.hpp"
#include "sensor/input_error.hpp"
#include "sim/scenario.hpp"
#include "sim/world_loader.hpp"

namespace lifelong {
namespace {

namespace fs = std::filesystem;

const std::string kDir = LIFELONG_SOURCE_DIR "/tests/data/fuzz_regressions/";
const std::string kScenarioDir = LIFELONG_SOURCE_DIR "/scenarios";

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void LoadWorld(const fs::path& p) { sim::LoadWorldFromString(ReadText(p), p.string()); }
void LoadScenario(const fs::path& p) {
  sim::LoadScenarioFromString(ReadText(p), p.string(), kScenarioDir);
}
void LoadCarmen(const fs::path& p) {
  for (auto recovery : {io::OdometryRecovery::kAuto, io::OdometryRecovery::kOn}) {
    io::CarmenReadOptions options;
    options.recovery = recovery;
    try {
      io::ReadCarmenLog(p.string(), options);
    } catch (const InputError&) {
    }
  }
}
void LoadGraph(const fs::path& p) { io::ReadGraphFile(p.string()); }
void LoadRelations(const fs::path& p) {
  for (const Relation& r : io::ReadRelations(p.string(), io::kIntelRelationsTimeOffsetS)) {
    EXPECT_TRUE(std::isfinite(r.t1_s) && std::isfinite(r.t2_s) && std::isfinite(r.T_1_2.x) &&
                std::isfinite(r.T_1_2.y) && std::isfinite(r.T_1_2.theta));
  }
}
void LoadTum(const fs::path& p) {
  for (const StampedPose& pose : io::ReadTum(p.string())) {
    const Pose2& T = pose.T_world_robot;
    EXPECT_TRUE(std::isfinite(pose.stamp_s) && std::isfinite(T.x) && std::isfinite(T.y) &&
                std::isfinite(T.theta));
  }
}
/// fuzz_map's input (fuzz/map_input.hpp): both halves from memory as the fuzzer does, then
/// as files through ReadPgmMap, the image written as fuzz_map.pgm next to the YAML.
void LoadMap(const fs::path& p) {
  const fuzz::MapInput input = fuzz::SplitMapInput(ReadText(p));
  io::MapYaml yaml;
  try {
    std::istringstream in(input.yaml);
    yaml = io::ParseMapYaml(in, p.string());
  } catch (const InputError&) {
  }
  try {
    std::istringstream in(input.pgm);
    io::ParsePgmImage(in, p.string(), yaml);
  } catch (const InputError&) {
  }
  const std::string dir = testing::TempDir();
  std::ofstream(dir + "fuzz_map.yaml", std::ios::binary) << input.yaml;
  std::ofstream(dir + "fuzz_map.pgm", std::ios::binary) << input.pgm;
  io::ReadPgmMap(dir + "fuzz_map.yaml");
}

/// Runs `load` on every file of the target's folder; returns how many files there were.
int RunAll(const std::string& target, const std::function<void(const fs::path&)>& load) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(kDir + target)) {
    ++n;
    SCOPED_TRACE(entry.path().string());
    try {
      load(entry.path());
    } catch (const InputError&) {
    }  // any other exception escapes and fails the test
  }
  return n;
}

TEST(FuzzRegression, WorldInputsLoadOrThrowInputError) { EXPECT_GT(RunAll("world", LoadWorld), 0); }
TEST(FuzzRegression, ScenarioInputsLoadOrThrowInputError) {
  EXPECT_GT(RunAll("scenario", LoadScenario), 0);
}
TEST(FuzzRegression, CarmenInputsLoadOrThrowInputError) {
  EXPECT_GT(RunAll("carmen", LoadCarmen), 0);
}
TEST(FuzzRegression, GraphInputsLoadOrThrowInputError) { EXPECT_GT(RunAll("graph", LoadGraph), 0); }
TEST(FuzzRegression, RelationsInputsLoadOrThrowInputError) {
  EXPECT_GT(RunAll("relations", LoadRelations), 0);
}
TEST(FuzzRegression, TumInputsLoadOrThrowInputError) { EXPECT_GT(RunAll("tum", LoadTum), 0); }
TEST(FuzzRegression, MapInputsLoadOrThrowInputError) { EXPECT_GT(RunAll("map", LoadMap), 0); }

/// The field an InputError names, or "<no error>".
std::string ErrorField(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.field();
  }
  return "<no error>";
}

TEST(FuzzRegression, ScenarioLimitsNameTheField) {
  const auto scenario = [](const std::string& file) {
    return [file] { LoadScenario(kDir + "scenario/" + file); };
  };
  EXPECT_EQ(ErrorField(scenario("huge_repetitions.yaml")), "route.repetitions");
  EXPECT_EQ(ErrorField(scenario("huge_tour_duration.yaml")), "route.duration_s");
  EXPECT_EQ(ErrorField(scenario("world_is_a_device.yaml")), "world");
  EXPECT_EQ(ErrorField(scenario("world_name_too_long.yaml")), "world");
  EXPECT_EQ(ErrorField(scenario("tour_only_start.yaml")), "route.places");
}

TEST(FuzzRegression, WorldNonFiniteNumbersNameTheField) {
  const auto world = [](const std::string& file) {
    return [file] { LoadWorld(kDir + "world/" + file); };
  };
  EXPECT_EQ(ErrorField(world("nonfinite_coordinates.yaml")), "walls[0].polyline");
  EXPECT_EQ(ErrorField(world("nonfinite_clearance_box.yaml")), "clearance_m");
}

TEST(FuzzRegression, MapSizesAndDevicesNameTheField) {
  const auto map = [](const std::string& file) {
    return [file] { LoadMap(kDir + "map/" + file); };
  };
  EXPECT_EQ(ErrorField(map("width_1e10.map")), "width");
  EXPECT_EQ(ErrorField(map("size_beyond_int.map")), "width");
  EXPECT_EQ(ErrorField(map("size_without_pixels.map")), "pixels");
  EXPECT_EQ(ErrorField(map("image_is_a_device.map")), "image");
}

TEST(FuzzRegression, TumHugeQuaternionGivesFiniteYaw) {
  const auto poses = io::ReadTum(kDir + "tum/huge_quaternion_nan_yaw.tum");
  ASSERT_EQ(poses.size(), 1u);
  EXPECT_NEAR(poses[0].T_world_robot.theta, 3.14159265358979323846 / 2, 1e-12);
}

TEST(FuzzRegression, GraphIdsNearInt64LimitsAreRejected) {
  const auto parse = [](const std::string& text) {
    return [text] {
      std::istringstream in(text);
      io::ParseGraph(in, "ids.g2o");
    };
  };
  EXPECT_EQ(ErrorField(parse("EDGE_SE2 9223372036854775807 5 1 0 0 1 0 0 1 0 1\n")), "from");
  EXPECT_EQ(ErrorField(parse("EDGE_SE2 4 -9223372036854775808 1 0 0 1 0 0 1 0 1\n")), "to");
  EXPECT_EQ(ErrorField(parse("EDGE_SE2 4 5 1 0 0 1 0 0 1 0 1\n")), "<no error>");
}

TEST(FuzzRegression, GraphCliqueNamingANodeTwiceIsRejected) {
  std::istringstream in("VERTEX_SE2 0 0 0 0\nLIFELONG_CLIQUE_SE2 2 0 0 1 0 0 1 0 0 1 0 1\n");
  EXPECT_THROW(io::ParseGraph(in, "clique.g2o"), InputError);
}

TEST(FuzzRegression, CarmenNulByteIsAnInputErrorOnItsLine) {
  const std::string path = testing::TempDir() + "nul.clf";
  {
    std::ofstream out(path, std::ios::binary);
    out << "ODOM 0 0 0 0 0 0 1.0 h 1.0\n" << std::string(1, '\0') << "ODOM 0 0 0\n";
  }
  try {
    io::ReadCarmenLog(path);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
  }
}

}  // namespace
}  // namespace lifelong
