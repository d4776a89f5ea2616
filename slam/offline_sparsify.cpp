#include "slam/offline_sparsify.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

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
  OfflineSparsifyStats stats;
  const auto start = std::chrono::steady_clock::now();
  for (NodeId k : remove) {
    if (!graph->HasNode(k)) {
      throw std::invalid_argument("SparsifyOffline: no node " + std::to_string(k));
    }
    const Replacement r = sparsifier.Replace(*graph, values, k);
    stats.max_clique = std::max(stats.max_clique, r.neighbours.size());
    stats.local_kl_sum += r.kl_divergence;
    if (r.regularized) ++stats.regularized;
    ApplyReplacement(graph, k, r);
    ++stats.removed;
  }
  stats.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace lifelong::slam
