// Helpers shared by the io tests: temporary files, whole-file reads, pose comparison and
// where the test data and the shared datasets are.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "sensor/pose2.hpp"

namespace lifelong::io::test_util {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
inline const std::string kData = std::string(LIFELONG_SOURCE_DIR) + "/tests/data/io/";
inline const std::string kDatasets = std::string(LIFELONG_SHARED_DIR) + "/datasets/";

inline std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "io_log_" + name;
}

inline std::string WriteText(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

inline std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline bool Exists(const std::string& path) { return std::ifstream(path).good(); }

inline void ExpectPose(const Pose2& p, double x, double y, double theta, double tol = 1e-9) {
  EXPECT_NEAR(p.x, x, tol);
  EXPECT_NEAR(p.y, y, tol);
  EXPECT_NEAR(NormalizeAngle(p.theta - theta), 0.0, tol);
}

}  // namespace lifelong::io::test_util
