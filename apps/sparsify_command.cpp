#include "apps/sparsify_command.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>
#include <vector>

#include "io/graph_file.hpp"
#include "io/output_path.hpp"
#include "sensor/input_error.hpp"
#include "slam/backend/optimizer.hpp"
#include "slam/marginal/global_kl.hpp"
#include "slam/sparsify/offline_sparsify.hpp"
#include "slam/sparsify/sparsifier.hpp"

namespace lifelong::apps {
namespace {

using slam::NodeId;

// The global KL compares marginals of the whole graph with one vertex held, which a graph in
// several pieces does not have: each piece floats free of the others.
void CheckConnected(const slam::PoseGraph& graph, const std::string& path) {
  const std::vector<NodeId> ids = graph.NodeIds();
  std::set<NodeId> reached{ids.front()};
  std::vector<NodeId> stack{ids.front()};
  while (!stack.empty()) {
    const NodeId u = stack.back();
    stack.pop_back();
    for (NodeId w : graph.Neighbours(u)) {
      if (reached.insert(w).second) stack.push_back(w);
    }
  }
  if (reached.size() == ids.size()) return;
  NodeId first = ids.front();
  for (NodeId id : ids) {
    if (!reached.count(id)) {
      first = id;
      break;
    }
  }
  throw InputError(path, 0, "",
                   "the graph is not connected: " + std::to_string(ids.size() - reached.size()) +
                       " vertices (the first " + std::to_string(first) +
                       ") cannot be reached from vertex " + std::to_string(ids.front()) +
                       " through its edges; sparsify needs one connected graph");
}

std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// Ids to remove, one or more per line (`#` starts a comment); each must be a node.
std::vector<NodeId> ReadRemoveFile(const std::string& path, const slam::PoseGraph& graph) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open the list of ids to remove");
  std::vector<NodeId> ids;
  std::set<NodeId> seen;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    std::istringstream words(text.substr(0, text.find('#')));
    for (std::string token; words >> token;) {
      char* end = nullptr;
      errno = 0;
      const long long id = std::strtoll(token.c_str(), &end, 10);
      if (*end != '\0' || errno == ERANGE) {
        throw InputError(path, line, "id", "not an integer id: '" + token + "'");
      }
      if (!graph.HasNode(id)) {
        throw InputError(path, line, "id", "node " + token + " is not in the graph");
      }
      if (!seen.insert(id).second) {
        throw InputError(path, line, "id", "node " + token + " is listed twice");
      }
      ids.push_back(id);
    }
  }
  return ids;
}

void PrintNumber(std::ostream& out, const char* key, double v) {
  out << ",\"" << key << "\":";
  if (std::isfinite(v)) {
    out << v;
  } else {
    out << "null";
  }
}

/// The sparsifier's settings from the options; InputError naming an unknown value.
slam::SparsifierConfig SparsifierSettings(const SparsifyArgs& args, const std::string& means) {
  slam::SparsifierConfig config;
  if (means == "estimate") {
    config.means = slam::FactorMeans::kEstimate;
  } else if (means == "gradient") {
    config.means = slam::FactorMeans::kGradient;
  } else if (means == "marginal_mean") {
    config.means = slam::FactorMeans::kMarginalMean;
  } else {
    throw InputError("--means", 0, "",
                     "unknown value '" + means + "' (known: estimate, gradient, marginal_mean)");
  }
  if (args.no_blanket) config.blanket = slam::BlanketPolicy::kFactorsAtK;
  if (args.nfr_chords == "mi") {
    config.nfr_chords = slam::NfrChords::kMutualInformation;
  } else if (args.nfr_chords != "joined") {
    throw InputError("--nfr-chords", 0, "",
                     "unknown value '" + args.nfr_chords + "' (known: joined, mi)");
  }
  return config;
}

/// The result line: one JSON object (docs/cli.md "sparsify").
void PrintResult(const SparsifyArgs& args, const std::string& means, const std::string& method,
                 const slam::PoseGraph& sparse, const slam::OfflineSparsifyStats& stats,
                 const slam::GlobalKl& kl) {
  std::ostringstream json;
  json << std::setprecision(10) << "{\"method\":\"" << method << "\",\"kept\":" << sparse.NumNodes()
       << ",\"removed\":" << stats.removed << ",\"edges\":" << sparse.NumEdgesForGamma()
       << ",\"factors\":" << sparse.edges().size() + sparse.cliques().size();
  PrintNumber(json, "time_s", stats.time_s);
  PrintNumber(json, "kld", kl.kl);
  PrintNumber(json, "kld_mean", kl.mean_term);
  PrintNumber(json, "rms_offset_m", kl.rms_offset_m);
  PrintNumber(json, "local_kl", stats.local_kl_sum);
  json << ",\"max_clique\":" << stats.max_clique << ",\"regularized\":" << stats.regularized
       << ",\"gradient_kept\":" << (means == "gradient" ? "true" : "false") << ",\"means\":\""
       << means << '"';
  if (args.method == "nfr-subgraph") json << ",\"nfr_chords\":\"" << args.nfr_chords << '"';
  json << ",\"blanket\":" << (args.no_blanket ? "false" : "true");
  json << "}\n";
  std::cout << json.str();
}

}  // namespace

int Sparsify(const SparsifyArgs& args) {
  const std::string means = args.zero_residual ? "estimate" : args.means;
  const slam::SparsifierConfig config = SparsifierSettings(args, means);
  if (!args.out.empty()) io::CheckWritableFile(args.out, "-o");  // before the work, not after
  const auto sparsifier = slam::MakeSparsifier(args.method, config);
  if (!sparsifier) {
    throw InputError(
        "--method", 0, "",
        "unknown method '" + args.method + "' (known: " + Join(slam::SparsifierNames()) + ")");
  }
  if (args.keep_share && !(*args.keep_share > 0.0 && *args.keep_share <= 1.0)) {
    std::ostringstream v;
    v << *args.keep_share;
    throw InputError("--keep-share", 0, "", "must be in (0, 1], got " + v.str());
  }
  if (!args.keep_share && args.remove.empty()) {
    throw InputError("sparsify", 0, "", "give --keep-share F or --remove FILE");
  }
  io::GraphFile file = io::ReadGraphFile(args.graph);
  slam::PoseGraph graph = slam::PoseGraph::FromFactors(file.factors);
  if (graph.NumNodes() == 0) throw InputError(args.graph, 0, "", "the graph has no vertices");
  CheckConnected(graph, args.graph);
  const std::vector<NodeId> remove =
      args.keep_share ? slam::RemovalForKeepShare(graph.NodeIds(), *args.keep_share)
                      : ReadRemoveFile(args.remove, graph);
  if (remove.size() == graph.NumNodes()) {
    throw InputError(args.remove, 0, "id", "every node would be removed");
  }
  slam::OptimizerParams params;  // plain least squares: no robust kernel
  slam::Optimize(graph, &file.values, params);
  const slam::PoseGraph& full = graph;
  const slam::Values& optimum = file.values;
  slam::PoseGraph sparse = full;
  const slam::OfflineSparsifyStats stats =
      slam::SparsifyOffline(&sparse, optimum, remove, *sparsifier);
  slam::Values sparse_values;
  for (NodeId id : sparse.NodeIds()) sparse_values[id] = optimum.at(id);
  slam::Optimize(sparse, &sparse_values, params);
  const slam::GlobalKl kl = slam::GlobalKlDivergence(full, optimum, sparse, sparse_values);
  if (!args.out.empty()) io::WriteG2o(args.out, sparse.Factors(), sparse_values);
  PrintResult(args, means, sparsifier->Name(), sparse, stats, kl);
  return 0;
}

}  // namespace lifelong::apps
