// Bad input met by the `lifelong` command as a whole process: each gives exit 2 and names
// the file and the field or line, before any work where it can, and leaves no output.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "run_lifelong.hpp"

namespace {

namespace fs = std::filesystem;

using lifelong::test::ExpectInputError;
using lifelong::test::Lifelong;
using lifelong::test::Result;
const std::string kSource = LIFELONG_SOURCE_DIR;
const std::string kScenario = kSource + "/scenarios/corridor_3.yaml";

fs::path Fresh(const std::string& name) { return lifelong::test::FreshPath("bad_input_", name); }

fs::path WriteFile(const std::string& name, const std::string& text) {
  return lifelong::test::WriteFresh("bad_input_", name, text);
}

// A log whose odometry jumps 100 km at its second scan would make a map of 2e6 x 2e6 cells:
// the run stops at that scan instead of exhausting memory at the end.
TEST(BadInputCli, AMapThatOutgrowsEveryMachineStopsTheRunAtItsScan) {
  const fs::path log = WriteFile("jump.clf",
                                 "FLASER 3 1 1 1 0 0 0 0 0 0 1.0 h 1.0\n"
                                 "FLASER 3 1 1 1 0 0 0 100000 100000 0 2.0 h 2.0\n");
  const fs::path out = Fresh("jump");
  const Result r = Lifelong("replay " + log.string() + " --modes standard -o " + out.string());
  ExpectInputError(r, log.string() + ": the scan stamped 2.000 s");
  EXPECT_NE(r.output.find("does the odometry jump?"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Directories given as input files are named by their option before any work.
TEST(BadInputCli, ADirectoryWhereAFileBelongsIsNamed) {
  const fs::path dir = Fresh("a_dir");
  fs::create_directories(dir);
  ExpectInputError(Lifelong("run " + dir.string() + " -o " + Fresh("o1").string()),
                   dir.string() + " is a directory");
  ExpectInputError(
      Lifelong("run " + kScenario + " --config " + dir.string() + " -o " + Fresh("o2").string()),
      "--config: " + dir.string() + " is a directory");
  ExpectInputError(Lifelong("optimize " + dir.string()), dir.string() + " is a directory");
  ExpectInputError(Lifelong("sweep " + dir.string() + " -o " + Fresh("o3").string()),
                   dir.string() + " is a directory");
}

// --frames naming a file, and --video under one, are refused before the simulation.
TEST(BadInputCli, FramesAndVideoPathsAreCheckedFirstAndNamed) {
  const fs::path file = WriteFile("afile.txt", "x");
  const fs::path out = Fresh("frames_out");
  Result r = Lifelong("run " + kScenario + " --modes standard --frames " + file.string() + " -o " +
                      out.string());
  ExpectInputError(r, "field '--frames'");
  EXPECT_EQ(r.output.find("simulating"), std::string::npos) << r.output;
  r = Lifelong("run " + kScenario + " --modes standard --video " + (file / "x.mp4").string() +
               " -o " + out.string());
  ExpectInputError(r, "field '--video'");
  EXPECT_FALSE(fs::exists(out));
}

// A graph in two pieces has no global KL; the error says why instead of an internal error.
TEST(BadInputCli, SparsifyNamesAGraphThatIsNotConnected) {
  const fs::path g = WriteFile("pieces.g2o",
                               "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nVERTEX_SE2 2 5 0 0\n"
                               "VERTEX_SE2 3 6 0 0\n"
                               "EDGE_SE2 0 1 1 0 0 100 0 0 100 0 100\n"
                               "EDGE_SE2 2 3 1 0 0 100 0 0 100 0 100\n");
  const Result r = Lifelong("sparsify " + g.string() + " --keep-share 0.5");
  ExpectInputError(r, g.string() + ": the graph is not connected: 2 vertices (the first 2)");
}

// Measurements and information past any physical magnitude are refused at their line: they
// overflowed the optimizer, which then reported convergence at a chi2 of NaN.
TEST(BadInputCli, GraphValuesPastAnyMagnitudeAreRefusedAtTheirLine) {
  const std::string head = "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n";
  const fs::path far = WriteFile("far.g2o", head + "EDGE_SE2 0 1 1e200 0 0 1 0 0 1 0 1\n");
  const fs::path out = Fresh("far_out.g2o");
  ExpectInputError(Lifelong("optimize " + far.string() + " -o " + out.string()),
                   far.string() + ":3: field 'dx'");
  EXPECT_FALSE(fs::exists(out));
  const fs::path sure = WriteFile("sure.g2o", head + "EDGE_SE2 0 1 1 0 0 1e300 0 0 1 0 1\n");
  ExpectInputError(Lifelong("sparsify " + sure.string() + " --keep-share 0.5"),
                   sure.string() + ":3: field 'I11'");
}

// A cell side of a micrometre is refused by the config reader (it filled 24 GB in one scan).
TEST(BadInputCli, ACellSideNoLaserResolvesIsRefused) {
  const fs::path config = WriteFile("tiny.yaml", "grid:\n  resolution_m: 1e-6\n");
  const Result r = Lifelong("run " + kScenario + " --modes standard --config " + config.string() +
                            " -o " + Fresh("tiny_out").string());
  ExpectInputError(r, config.string() + ":2: field 'grid.resolution_m'");
}

}  // namespace
