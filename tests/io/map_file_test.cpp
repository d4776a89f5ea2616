// Tests for io/map_file: ROS map_server PGM + YAML on a 3x2 grid worked out by hand.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/map_file.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

std::string TempPath(const std::string& name) { return ::testing::TempDir() + "io_map_" + name; }

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Row 0 is the lowest y:  row 1: [0.5, 0.1, 1.0]   (0.5 is neither free nor occupied)
//                         row 0: [0.0, 0.9, unknown]
OccupancyGrid SmallGrid() {
  OccupancyGrid g;
  g.width = 3;
  g.height = 2;
  g.resolution_m = 0.1;
  g.origin_x_m = -1.5;
  g.origin_y_m = 2.25;
  g.p_occ = {0.0f, 0.9f, OccupancyGrid::kUnknown, 0.5f, 0.1f, 1.0f};
  return g;
}

TEST(MapFile, WritesFlippedTrinaryPgmAndYaml) {
  const MapFilePaths paths = WritePgmMap(TempPath("small.pgm"), SmallGrid());
  EXPECT_EQ(paths.pgm, TempPath("small.pgm"));
  EXPECT_EQ(paths.yaml, TempPath("small.yaml"));
  // Image row 0 = grid row 1 (top): unknown(0.5)=205, free=254, occupied=0; then grid row 0.
  const std::string expected_pgm = std::string("P5\n3 2\n255\n") +
                                   std::string{char(205), char(254), char(0)} +
                                   std::string{char(254), char(0), char(205)};
  EXPECT_EQ(ReadBytes(paths.pgm), expected_pgm);
  EXPECT_EQ(ReadBytes(paths.yaml),
            "image: io_map_small.pgm\nresolution: 0.1\norigin: [-1.5, 2.25, 0.0]\nnegate: 0\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
}

TEST(MapFile, RoundTripGivesTrinaryGrid) {
  const MapFilePaths paths = WritePgmMap(TempPath("rt"), SmallGrid());
  const OccupancyGrid g = ReadPgmMap(paths.yaml);
  ASSERT_EQ(g.width, 3);
  ASSERT_EQ(g.height, 2);
  EXPECT_DOUBLE_EQ(g.resolution_m, 0.1);
  EXPECT_DOUBLE_EQ(g.origin_x_m, -1.5);
  EXPECT_DOUBLE_EQ(g.origin_y_m, 2.25);
  const float u = OccupancyGrid::kUnknown;
  const std::vector<float> expected = {0.0f, 1.0f, u, u, 0.0f, 1.0f};
  EXPECT_EQ(g.p_occ, expected);
}

TEST(MapFile, ReadsHandWrittenMapServerFiles) {
  // A GIMP-style header comment, negate: 1 (bright = occupied), quoted image name.
  WriteBytes(TempPath("neg.pgm"),
             std::string("P5\n# made by hand\n2 1\n255\n") + std::string{char(255), char(0)});
  WriteBytes(TempPath("neg.yaml"),
             "image: \"io_map_neg.pgm\"\nresolution: 0.05\norigin: [1.0, -2.0, 0.0]  # m\n"
             "negate: 1\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const OccupancyGrid g = ReadPgmMap(TempPath("neg.yaml"));
  ASSERT_EQ(g.p_occ.size(), 2u);
  EXPECT_EQ(g.p_occ[0], 1.0f);
  EXPECT_EQ(g.p_occ[1], 0.0f);
  EXPECT_DOUBLE_EQ(g.origin_y_m, -2.0);
}

/// Expects ReadPgmMap to throw an InputError naming `field` (and `line` when > 0).
void ExpectMapError(const std::string& yaml, const std::string& pgm, int line,
                    const std::string& field) {
  WriteBytes(TempPath("bad.pgm"), pgm);
  WriteBytes(TempPath("bad.yaml"), yaml);
  try {
    ReadPgmMap(TempPath("bad.yaml"));
    ADD_FAILURE() << "no InputError for:\n" << yaml;
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_EQ(e.line(), line) << e.what();
  }
}

TEST(MapFile, BadInputThrowsWithFieldAndLine) {
  const std::string pgm = std::string("P5\n2 1\n255\n") + std::string{char(0), char(254)};
  const std::string image = "image: io_map_bad.pgm\n";
  ExpectMapError(image + "origin: [0, 0, 0]\n", pgm, 0, "resolution");
  ExpectMapError(image + "resolution: 0.05\norigin: [0, 0]\n", pgm, 3, "origin");
  ExpectMapError(image + "resolution: abc\norigin: [0, 0, 0]\n", pgm, 2, "resolution");
  ExpectMapError(image + "resolution: 0.05\norigin: [0, 0, 0]\nmode: scale\n", pgm, 4, "mode");
  const std::string ok = image + "resolution: 0.05\norigin: [0, 0, 0]\n";
  ExpectMapError(ok, std::string("P5\n2 1\n255\n") + char(0), 0, "pixels");
  ExpectMapError(ok, "P2\n2 1\n255\n0 254\n", 1, "magic");
  EXPECT_THROW(ReadPgmMap(TempPath("missing.yaml")), InputError);
  EXPECT_THROW(WritePgmMap(TempPath("no_dir/m"), SmallGrid()), InputError);
}

TEST(MapFile, StreamHalvesGiveTheSameGridAsTheFiles) {
  const MapFilePaths paths = WritePgmMap(TempPath("streams"), SmallGrid());
  std::istringstream yaml_in(ReadBytes(paths.yaml));
  const MapYaml yaml = ParseMapYaml(yaml_in, "mem.yaml");
  EXPECT_EQ(yaml.image, "io_map_streams.pgm");
  EXPECT_EQ(yaml.image_line, 1);
  std::istringstream pgm_in(ReadBytes(paths.pgm));
  const OccupancyGrid g = ParsePgmImage(pgm_in, "mem.pgm", yaml);
  EXPECT_EQ(g.p_occ, ReadPgmMap(paths.yaml).p_occ);
  EXPECT_EQ(g.width, 3);
  EXPECT_DOUBLE_EQ(g.origin_x_m, -1.5);
}

// Found by review: a value opening with a quote lost its last character even when that
// was not the closing quote (`image: "map.pgm` named `map.pg`).
TEST(MapFile, OnlyMatchingQuotesAreStripped) {
  const auto image = [](const std::string& value) {
    std::istringstream in("resolution: 1\norigin: [0, 0, 0]\nimage: " + value + "\n");
    return ParseMapYaml(in, "q.yaml").image;
  };
  EXPECT_EQ(image("\"map.pgm\""), "map.pgm");
  EXPECT_EQ(image("'map.pgm'"), "map.pgm");
  EXPECT_EQ(image("\"map.pgm"), "\"map.pgm");
  EXPECT_EQ(image("'map.pgm\""), "'map.pgm\"");
}

/// The field ParsePgmImage names for a bad `header` (followed by two pixel bytes).
std::string PgmHeaderError(const std::string& header) {
  std::istringstream in(header + std::string(2, '\0'));
  try {
    ParsePgmImage(in, "mem.pgm", MapYaml{});
  } catch (const InputError& e) {
    return e.field();
  }
  return "<no error>";
}

// Found by review while fuzzing: the size went through static_cast<int>(double), undefined
// for 1e10 (UBSan: "outside the range of representable values of type 'int'"), and 2.5
// was read as 2. A size whose pixels are not there is read in 1 MiB chunks and rejected.
TEST(MapFile, PgmSizesAreIntegersInRange) {
  EXPECT_EQ(PgmHeaderError("P5\n2 1\n255\n"), "<no error>");
  EXPECT_EQ(PgmHeaderError("P5\n1e10 1\n255\n"), "width");
  EXPECT_EQ(PgmHeaderError("P5\n2.5 1\n255\n"), "width");
  EXPECT_EQ(PgmHeaderError("P5\n2 -1\n255\n"), "height");
  EXPECT_EQ(PgmHeaderError("P5\n2 3000000000\n255\n"), "height");
  EXPECT_EQ(PgmHeaderError("P5\n2 1\n256\n"), "maxval");
  EXPECT_EQ(PgmHeaderError("P5\n65536 65536\n255\n"), "height");  // > 2^31 - 1 cells
  EXPECT_EQ(PgmHeaderError("P5\n46340 46340\n255\n"), "pixels");
  EXPECT_EQ(PgmHeaderError("P5 #c\n#\n2#x\n"), "width");
  EXPECT_EQ(PgmHeaderError("P5\n2 1\n" + std::string(40, '1')), "maxval");
}

// A resolution or origin near the double's limit passed the YAML checks and gave a map whose
// far edge was infinite.
TEST(MapFile, MapExtentMustBeFinite) {
  MapYaml yaml;
  yaml.resolution_m = 1e308;
  std::istringstream in("P5\n2 1\n255\n" + std::string(2, '\0'));
  try {
    ParsePgmImage(in, "mem.pgm", yaml);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "resolution");
  }
  yaml.resolution_m = 0.05;
  yaml.origin_x_m = 1.7e308;
  std::istringstream ok("P5\n2 1\n255\n" + std::string(2, '\0'));
  EXPECT_NO_THROW(ParsePgmImage(ok, "mem.pgm", yaml));  // finite: 1.7e308 + 0.1
}

// Found by review while fuzzing: the image named by the YAML was read whole, so
// `image: /dev/zero` allocated until std::bad_alloc (and a FIFO would block).
TEST(MapFile, ImageMustBeARegularFile) {
  const std::vector<std::string> images = {"/dev/zero", "/dev/null", ::testing::TempDir(),
                                           "none.pgm"};
  for (const std::string& image : images) {
    WriteBytes(TempPath("dev.yaml"), "resolution: 0.05\norigin: [0, 0, 0]\nimage: " + image + "\n");
    try {
      ReadPgmMap(TempPath("dev.yaml"));
      ADD_FAILURE() << image;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "image") << e.what();
      EXPECT_EQ(e.line(), 3) << e.what();
    }
  }
}

}  // namespace
}  // namespace lifelong::io
