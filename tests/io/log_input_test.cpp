// Tests for the input checks of issue #13: scans with no beams, scans stamped backwards,
// and the relations clock (offset detection), on tiny hand-made files.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "io/carmen_log.hpp"
#include "io/relations.hpp"
#include "io/relations_offset.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

const std::string kDatasets = std::string(LIFELONG_SHARED_DIR) + "/datasets/";

std::string WriteText(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "io_input_" + name;
  std::ofstream(path) << text;
  return path;
}

// FLASER n r.. x y theta odom_x odom_y odom_theta ipc host logger
std::string Flaser(double stamp) {
  return "FLASER 3 1.0 1.0 1.0 0 0 0 0 0 0 " + std::to_string(stamp) + " host " +
         std::to_string(stamp) + "\n";
}

TEST(LogInput, ScanWithZeroBeamsNamesTheLine) {
  const std::string path =
      WriteText("zero.clf", Flaser(1.0) + "FLASER 0 0 0 0 0 0 0 2.0 host 2.0\n");
  try {
    ReadCarmenLog(path);
    FAIL() << "a scan with 0 beams was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(":2"), std::string::npos) << what;
    EXPECT_NE(what.find("0 beams"), std::string::npos) << what;
  }
}

TEST(LogInput, RobotLaserWithZeroBeamsIsAnInputError) {
  const std::string line =
      "ROBOTLASER1 0 -1.5708 3.1416 0.0175 80 0.01 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 1.0 host "
      "1.0\n";
  EXPECT_THROW(ReadCarmenLog(WriteText("zero_rl.clf", line)), InputError);
}

TEST(LogInput, BackwardStampsAreCountedWithTheFirstLine) {
  const std::string path = WriteText("backward.clf", "# comment\n" + Flaser(1.0) + Flaser(3.0) +
                                                         Flaser(2.0) + Flaser(4.0) + Flaser(0.5));
  const CarmenLog log = ReadCarmenLog(path);
  ASSERT_EQ(log.observations.size(), 5u);
  EXPECT_EQ(log.backward_scan_stamps, 2);
  EXPECT_EQ(log.first_backward_scan_line, 4);  // the scan stamped 2.0
}

TEST(LogInput, NoBackwardStampsMeansLineZero) {
  const CarmenLog log = ReadCarmenLog(WriteText("forward.clf", Flaser(1.0) + Flaser(2.0)));
  EXPECT_EQ(log.backward_scan_stamps, 0);
  EXPECT_EQ(log.first_backward_scan_line, 0);
}

TEST(RelationsOffset, FindsTheOffsetThatPutsStampsOnScans) {
  const double offset = 976052857.337284;
  const std::vector<double> scans{0.5, 1.25, 2.0, 2.75, 3.5, 4.0, 4.5};
  std::vector<Relation> rel{{offset + 0.5, offset + 2.0, {}},
                            {offset + 1.25, offset + 4.5, {}},
                            {offset + 2.75, offset + 3.5, {}},
                            {offset + 4.0, offset + 99.0, {}}};  // second stamp off the log
  const OffsetDetection d = DetectRelationsOffset(rel, scans);
  EXPECT_NEAR(d.offset_s, offset, 1e-6);
  EXPECT_EQ(d.matched, 3u);
  EXPECT_EQ(CountMatchedRelations(rel, scans, 0.0), 0u);
  const auto shifted = ShiftRelations(rel, d.offset_s);
  EXPECT_NEAR(shifted[0].t1_s, 0.5, 1e-6);
}

TEST(RelationsOffset, IsCentredOnTheStampsNotOnOneAnchor) {
  // Relation stamps carry +-0.4 ms of rounding; each anchor alone is up to 0.4 ms off.
  const std::vector<double> scans{0.13, 0.71, 1.42, 1.9, 2.66, 3.05, 3.81, 4.27};
  const double jitter[] = {0.0004, -0.0001, 0.0, 0.0002, -0.0003, 0.0001, -0.0002, 0.0003};
  std::vector<Relation> rel;
  for (std::size_t i = 0; i + 1 < scans.size(); ++i) {
    rel.push_back({500.0 + scans[i] + jitter[i], 500.0 + scans[i + 1] + jitter[i + 1], {}});
  }
  const OffsetDetection d = DetectRelationsOffset(rel, scans);
  EXPECT_EQ(d.matched, rel.size());
  EXPECT_NEAR(d.offset_s, 500.0, 1e-4);
}

TEST(RelationsOffset, PrefersZeroWhenTheFileUsesLogTime) {
  // Evenly spaced scans: offsets of whole steps also fit some relations, but 0 fits all.
  std::vector<double> scans;
  for (int i = 0; i < 20; ++i) scans.push_back(i * 0.5);
  const std::vector<Relation> rel{{0.0, 9.5, {}}, {1.0, 2.0, {}}, {3.5, 4.0, {}}};
  const OffsetDetection d = DetectRelationsOffset(rel, scans);
  EXPECT_EQ(d.offset_s, 0.0);
  EXPECT_EQ(d.matched, 3u);
}

TEST(RelationsOffset, RegularScansInAnotherClockAreAmbiguous) {
  // Scans every 0.5 s: shifting the relations by whole periods fits them all as well.
  std::vector<double> scans;
  for (int i = 0; i < 20; ++i) scans.push_back(i * 0.5);
  const std::vector<Relation> rel{{100.0, 101.0, {}}, {101.5, 102.0, {}}};
  const OffsetDetection d = DetectRelationsOffset(rel, scans);
  EXPECT_EQ(d.matched, 2u);
  EXPECT_TRUE(d.also_fits_s.has_value());
}

TEST(RelationsOffset, NothingFitsGivesNoMatch) {
  const std::vector<double> scans{0.0, 1.0, 2.0};
  const std::vector<Relation> rel{{0.3, 5.7, {}}};
  EXPECT_EQ(DetectRelationsOffset(rel, scans).matched, 0u);
  EXPECT_EQ(DetectRelationsOffset({}, scans).matched, 0u);
}

TEST(RelationsOffset, IntelRawLogGivesTheKnownOffset) {
  const std::string log_path = kDatasets + "intel/intel-raw-first1088s.clf.gz";
  if (!std::ifstream(log_path).good()) GTEST_SKIP() << "shared datasets absent: " << kDatasets;
  const CarmenLog log = ReadCarmenLog(log_path);
  std::vector<double> stamps;
  for (const auto& o : log.observations) stamps.push_back(o.stamp_s);
  std::sort(stamps.begin(), stamps.end());
  const auto rel = ReadRelations(kDatasets + "intel/intel.relations", 0.0);
  const OffsetDetection d = DetectRelationsOffset(rel, stamps);
  // Centred on the stamps, not merely within the matching tolerance: where two scans are
  // close in time, 1 ms off picks other scans (relation error 0.038 instead of 0.029 m).
  EXPECT_NEAR(d.offset_s, kIntelRelationsTimeOffsetS, 1e-5);
  EXPECT_EQ(d.matched, 1030u);
}

}  // namespace
}  // namespace lifelong::io
