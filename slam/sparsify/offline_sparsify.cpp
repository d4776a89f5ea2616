#include "slam/sparsify/offline_sparsify.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "slam/sparsify/set_marginal.hpp"

namespace lifelong::slam {

std::vector<NodeId> RemovalForKeepShare(const std::vector<NodeId>& ids, double keep_share) {
  if (!(keep_share > 0.0 && keep_share <= 1.0)) {
    throw std::invalid_argument("RemovalForKeepShare: keep_share must be in (0, 1]");
  }
  const std::size_t n = ids.size();
  if (n == 0) return {};
  const auto kept = std::max<std::size_t>(
      1, std::min(n, static_cast<std::size_t>(std::llround(keep_share * static_cast<double>(n)))));
  std::vector<bool> keep(n, false);
  for (std::size_t i = 0; i < kept; ++i) keep[i * n / kept] = true;
  std::vector<NodeId> remove;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep[i]) remove.push_back(ids[i]);
  }
  return remove;
}

OfflineSparsifyStats SparsifyOffline(PoseGraph* graph, const Values& values,
                                     std::vector<NodeId> remove, const Sparsifier& sparsifier) {
  std::sort(remove.begin(), remove.end());
  remove.erase(std::unique(remove.begin(), remove.end()), remove.end());
  for (NodeId k : remove) {
    if (!graph->HasNode(k)) {
      throw std::invalid_argument("SparsifyOffline: no node " + std::to_string(k));
    }
  }
  OfflineSparsifyStats stats;
  const auto start = std::chrono::steady_clock::now();
  const auto note = [&stats](const Replacement& r, std::size_t nodes) {
    stats.max_clique = std::max(stats.max_clique, r.neighbours.size());
    stats.local_kl_sum += r.kl_divergence;
    if (r.regularized) ++stats.regularized;
    stats.removed += nodes;
  };
  const auto one_at_a_time = [&](const std::vector<NodeId>& nodes) {
    for (NodeId k : nodes) {
      const Replacement r = sparsifier.Replace(*graph, values, k);
      note(r, 1);
      ApplyReplacement(graph, k, r);
    }
  };
  // The order matters to the approximating methods, so they keep the ascending order. The
  // exact ones go connected set by connected set: one set's marginal does not depend on the
  // others', and within a set the order is immaterial (set_marginal.hpp).
  if (!sparsifier.ReplacesSets()) {
    one_at_a_time(remove);
  } else {
    for (const std::vector<NodeId>& set : ConnectedSets(*graph, remove)) {
      std::optional<Replacement> r;
      if (set.size() >= 2) r = sparsifier.ReplaceSet(*graph, values, set);
      if (!r) {
        one_at_a_time(set);
        continue;
      }
      note(*r, set.size());
      ApplySetReplacement(graph, set, *r);
    }
  }
  stats.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace lifelong::slam
