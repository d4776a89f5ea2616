// Published figures keyed by relations file and log (eval/figures/reference_figures.hpp), and the
// build provenance (eval/report/build_info.hpp, cmake/WriteBuildInfo.cmake).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "eval/figures/reference_figures.hpp"
#include "eval/report/build_info.hpp"

namespace lifelong::eval {
namespace {

namespace fs = std::filesystem;

TEST(ReferenceFiguresTest, IntelRelationsGiveThePublishedRelationErrors) {
  const auto r = FindReferenceFigures("../shared/datasets/intel/intel.relations",
                                      "../shared/datasets/intel/intel-raw-first1088s.clf.gz");
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->dataset, "Intel Research Lab");
  ASSERT_GE(r->relation_errors.size(), 2u);
  bool graph_mapping = false, cartographer = false;
  for (const PublishedRelationError& e : r->relation_errors) {
    EXPECT_FALSE(e.citation.empty()) << e.method;
    if (e.method == "Graph mapping") {
      graph_mapping = true;
      EXPECT_DOUBLE_EQ(e.trans_mean_m, 0.031);  // Kümmerle et al. 2009
      EXPECT_NE(e.citation.find("Kümmerle"), std::string::npos);
    }
    if (e.method == "Cartographer") {
      cartographer = true;
      EXPECT_DOUBLE_EQ(e.trans_mean_m, 0.0229);  // Hess et al. 2016
      EXPECT_NE(e.citation.find("Hess"), std::string::npos);
    }
  }
  EXPECT_TRUE(graph_mapping);
  EXPECT_TRUE(cartographer);
  EXPECT_FALSE(r->notes.empty());  // the seed's Intel figures
}

TEST(ReferenceFiguresTest, LogsWithoutRelationsGetOnlyTheSeedsNotes) {
  const auto fhw = FindReferenceFigures("", "fhw-corrected.log.gz");
  ASSERT_TRUE(fhw.has_value());
  EXPECT_TRUE(fhw->relation_errors.empty());
  ASSERT_EQ(fhw->notes.size(), 1u);
  EXPECT_NE(fhw->notes[0].find("21 %"), std::string::npos);
  const auto intel = FindReferenceFigures("", "intel-corrected.log.gz");
  ASSERT_TRUE(intel.has_value());
  EXPECT_TRUE(intel->relation_errors.empty());
  EXPECT_FALSE(FindReferenceFigures("", "scenarios/corridor_3.yaml").has_value());
  EXPECT_FALSE(FindReferenceFigures("other.relations", "mylog.clf").has_value());
}

TEST(BuildInfoTest, VersionAndCommitOfTheCheckout) {
  const BuildInfo b = GetBuildInfo();
  EXPECT_EQ(b.version, LIFELONG_TEST_PROJECT_VERSION);
  EXPECT_FALSE(b.commit.empty());
  const std::string probe = "git -C '" LIFELONG_SOURCE_DIR "' rev-parse HEAD >/dev/null 2>&1";
  if (std::system(probe.c_str()) == 0) {
    EXPECT_NE(b.commit, "unknown");
  }
}

TEST(BuildInfoTest, ScriptSaysUnknownOutsideAGitCheckout) {
  const fs::path dir = fs::temp_directory_path() / "lifelong_build_info_not_git";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out = dir / "info.hpp";
  const std::string cmd = std::string("'") + LIFELONG_CMAKE_COMMAND +
                          "' -DSOURCE_DIR=" + dir.string() + " -DOUTPUT=" + out.string() +
                          " -DVERSION=9.8.7 -P '" LIFELONG_SOURCE_DIR
                          "/cmake/WriteBuildInfo.cmake' >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("#define LIFELONG_VERSION \"9.8.7\""), std::string::npos);
  EXPECT_NE(text.str().find("#define LIFELONG_COMMIT \"unknown\""), std::string::npos);
}

}  // namespace
}  // namespace lifelong::eval
