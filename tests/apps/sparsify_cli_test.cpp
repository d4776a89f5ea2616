// `lifelong sparsify` as a process: its JSON, its output graph and its input errors (exit 2
// naming the file, line and field).
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string out;  // stdout only
  std::string err;
};

/// A file of this process in the test temp directory: ctest runs the tests of this file as
/// parallel processes, which must not share one.
fs::path Temp(const std::string& name) {
  return fs::path(::testing::TempDir()) / ("sparsify_" + std::to_string(getpid()) + "_" + name);
}

Result Lifelong(const std::string& args) {
  const fs::path err = Temp("cli_err.txt");
  const std::string cmd = std::string(LIFELONG_BIN) + " " + args + " 2>" + err.string();
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof(buf), p)) > 0;) r.out.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  std::ifstream in(err);
  r.err.assign(std::istreambuf_iterator<char>(in), {});
  return r;
}

/// A ring of 12 poses on a circle with noisy closures: small, loopy, inconsistent.
fs::path Ring() {
  const fs::path p = Temp("ring.g2o");
  std::ofstream out(p);
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    out << "VERTEX_SE2 " << i << ' ' << 5 * std::cos(a) << ' ' << 5 * std::sin(a) << ' '
        << a + M_PI / 2 << '\n';
  }
  const double step = 2.0 * 5 * std::sin(M_PI / n);
  for (int i = 0; i < n; ++i) {
    out << "EDGE_SE2 " << i << ' ' << (i + 1) % n << ' ' << step + 0.01 * (i % 3) << " 0.02 "
        << 2 * M_PI / n << " 100 0 0 100 0 400\n";
  }
  const double phi = 2.0 * M_PI * 3 / n;  // chords i -> i + 3, with a small bias
  for (int i = 0; i + 3 < n; ++i) {
    const double chord = 10 * std::sin(phi / 2);
    out << "EDGE_SE2 " << i << ' ' << i + 3 << ' ' << chord * std::cos(phi / 2) + 0.03 << ' '
        << chord * std::sin(phi / 2) << ' ' << phi << " 50 0 0 50 0 200\n";
  }
  return p;
}

TEST(SparsifyCli, PrintsOneJsonObjectAndWritesTheKeptGraph) {
  const fs::path graph = Ring();
  const fs::path out = Temp("out.g2o");
  for (const char* method :
       {"naive", "exact", "chow-liu", "glc-dense", "glc", "nfr-tree", "nfr-subgraph"}) {
    fs::remove(out);
    const Result r = Lifelong("sparsify " + graph.string() + " --method " + method +
                              " --keep-share 0.5 -o " + out.string());
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["method"], method);
    EXPECT_EQ(j["kept"], 6);
    EXPECT_EQ(j["removed"], 6);
    EXPECT_GE(j["time_s"].get<double>(), 0.0);
    ASSERT_TRUE(j["kld"].is_number()) << method;
    const double kld = j["kld"];
    if (std::string(method) == "exact" || std::string(method) == "glc-dense") {
      EXPECT_LT(kld, 1e-6) << method;
    } else {
      EXPECT_GT(kld, 1e-6) << method;
    }
    std::ifstream in(out);
    std::string line;
    int vertices = 0;
    while (std::getline(in, line)) vertices += line.rfind("VERTEX_SE2 ", 0) == 0 ? 1 : 0;
    EXPECT_EQ(vertices, 6) << method;
  }
}

TEST(SparsifyCli, NfrTreeIsNoWorseThanChowLiuAndTheSubgraphNoWorseThanTheTree) {
  // NFR's tree informations are KL-optimal for the Chow-Liu tree, which chow-liu's exact pair
  // conditionals already are (slam/sparsify/nfr.hpp step 4): the two agree to rounding; the
  // subgraph's extra edges (--nfr-chords mi: the ring's cliques are trees before each removal, so
  // the joined pairs are all tree pairs) lower the KL.
  const fs::path graph = Ring();
  const auto run = [&](const std::string& method) {
    const Result r =
        Lifelong("sparsify " + graph.string() + " --method " + method + " --keep-share 0.5");
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto cl = run("chow-liu");
  const auto tree = run("nfr-tree");
  const auto joined = run("nfr-subgraph");
  const auto mi = run("nfr-subgraph --nfr-chords mi");
  EXPECT_EQ(tree["method"], "nfr-tree");
  ASSERT_TRUE(tree["kld"].is_number());
  ASSERT_TRUE(cl["kld"].is_number());
  ASSERT_TRUE(mi["kld"].is_number());
  const double kld = tree["kld"];
  EXPECT_TRUE(std::isfinite(kld));
  EXPECT_GT(kld, 1e-6);
  EXPECT_LE(kld, cl["kld"].get<double>() * (1.0 + 1e-6) + 1e-9);
  EXPECT_EQ(tree["edges"], cl["edges"]);
  EXPECT_EQ(joined["nfr_chords"], "joined");
  EXPECT_LE(joined["kld"].get<double>(), kld * (1.0 + 1e-6) + 1e-9);
  EXPECT_EQ(mi["nfr_chords"], "mi");
  EXPECT_LT(mi["kld"].get<double>(), kld);
  EXPECT_GT(mi["edges"].get<int>(), tree["edges"].get<int>());
  // The method list of --help and of the error for an unknown method come from the registry.
  const Result help = Lifelong("sparsify --help");
  EXPECT_NE(help.out.find("nfr-tree"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("nfr-subgraph"), std::string::npos) << help.out;
  const Result bad = Lifelong("sparsify " + graph.string() + " --method nfr --keep-share 0.5");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("nfr-subgraph"), std::string::npos) << bad.err;
  const Result chords = Lifelong("sparsify " + graph.string() +
                                 " --method nfr-subgraph --nfr-chords all --keep-share 0.5");
  EXPECT_EQ(chords.code, 2);
  EXPECT_NE(chords.err.find("--nfr-chords"), std::string::npos) << chords.err;
}

// --means: where the new factors put their minimum. For an exact method the marginal's mean
// and its gradient give the same factors (KLD 0 either way); estimate is --zero-residual;
// an unknown value, or both flags, exit 2 naming the option.
TEST(SparsifyCli, MeansPicksWhereTheNewFactorsPutTheirMinimum) {
  const fs::path graph = Ring();
  const auto run = [&](const std::string& args) {
    const Result r = Lifelong("sparsify " + graph.string() + " --keep-share 0.5 " + args);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto gradient = run("--method exact");
  const auto mean = run("--method exact --means marginal_mean");
  EXPECT_EQ(gradient["means"], "gradient");
  EXPECT_EQ(mean["means"], "marginal_mean");
  EXPECT_NEAR(mean["kld"].get<double>(), gradient["kld"].get<double>(), 1e-9);
  EXPECT_LT(mean["kld"].get<double>(), 1e-6);
  const auto estimate = run("--method chow-liu --means estimate");
  const auto zero = run("--method chow-liu --zero-residual");
  EXPECT_EQ(estimate["means"], "estimate");
  EXPECT_EQ(estimate["gradient_kept"], false);
  EXPECT_EQ(estimate["kld"], zero["kld"]);
  const Result bad =
      Lifelong("sparsify " + graph.string() + " --method chow-liu --keep-share 0.5 --means median");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--means"), std::string::npos) << bad.err;
  const Result both =
      Lifelong("sparsify " + graph.string() +
               " --method chow-liu --keep-share 0.5 --zero-residual --means gradient");
  EXPECT_EQ(both.code, 2);
}

// --no-blanket keeps the factors among the removed node's neighbours: chow-liu then replaces
// only the factors at k, so the ring's chords survive as they were and the graph keeps more
// edges; exact has no blanket either way (byte-identical output).
TEST(SparsifyCli, NoBlanketKeepsTheFactorsAmongTheNeighbours) {
  const fs::path graph = Ring();
  const auto run = [&](const std::string& args) {
    const Result r = Lifelong("sparsify " + graph.string() + " --keep-share 0.5 " + args);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto blanket = run("--method chow-liu");
  const auto at_k = run("--method chow-liu --no-blanket");
  EXPECT_EQ(blanket["blanket"], true);
  EXPECT_EQ(at_k["blanket"], false);
  EXPECT_GT(at_k["edges"].get<int>(), blanket["edges"].get<int>());
  EXPECT_GT(at_k["kld"].get<double>(), 1e-6);
  EXPECT_EQ(run("--method exact")["kld"], run("--method exact --no-blanket")["kld"]);
}

TEST(SparsifyCli, BadInputExitsTwoNamingTheField) {
  const fs::path graph = Ring();
  Result r = Lifelong("sparsify " + graph.string() + " --method glc --keep-share 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--keep-share"), std::string::npos) << r.err;
  r = Lifelong("sparsify " + graph.string() + " --method glc --keep-share 1.5");
  EXPECT_EQ(r.code, 2);
  r = Lifelong("sparsify " + graph.string() + " --method dense --keep-share 0.5");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("glc-dense"), std::string::npos) << r.err;  // lists the known ones
  const fs::path list = Temp("remove.txt");
  std::ofstream(list) << "1 2\n# comment\n3 99\n";
  r = Lifelong("sparsify " + graph.string() + " --method exact --remove " + list.string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(list.string() + ":3: field 'id'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("99"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
  std::ofstream(list) << "1 2 3\n";
  r = Lifelong("sparsify " + graph.string() + " --method exact --remove " + list.string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["kept"], 9);
}

}  // namespace
