// The per-mode CSVs; see mode_csv.hpp.
#include "eval/experiment/mode_csv.hpp"

#include <cmath>
#include <cstdio>

#include "io/atomic_file.hpp"

namespace lifelong::eval {

void WriteMarginalizations(const std::string& path, const slam::Mapper& mapper) {
  std::string text = "node,clique_size,kl_nats,information_gain_bits\n";
  char line[128];
  for (const auto& m : mapper.marginalizations()) {
    std::snprintf(line, sizeof(line), "%lld,%zu,%.9g,%.9g\n", static_cast<long long>(m.node),
                  m.clique_size, m.kl_divergence, m.information_gain_bits);
    text += line;
  }
  io::WriteFileAtomically(path, text);
}

void WriteSparsifications(const std::string& path, const slam::Mapper& mapper) {
  std::string text = "centre,nodes,edges_before,edges_after,kl_nats\n";
  char line[128];
  for (const auto& s : mapper.sparsifications()) {
    std::snprintf(line, sizeof(line), "%lld,%zu,%zu,%zu,%.9g\n", static_cast<long long>(s.centre),
                  s.nodes, s.edges_before, s.edges_after, s.kl_divergence);
    text += line;
  }
  io::WriteFileAtomically(path, text);
}

void WriteLoopAttempts(const std::string& path, const std::vector<LoopAttemptRow>& rows) {
  std::string text =
      "obs,node,search,candidates,old,window_m,window_rad,score,outcome,accepted,ambiguity\n";
  char line[192];
  for (const LoopAttemptRow& r : rows) {
    const slam::LoopAttempt& a = r.attempt;
    const char* search = slam::SearchName(a.search);
    const char* outcome =
        a.refused ? slam::MatchRefusalName(*a.refused) : (a.proposed ? "proposed" : "none");
    char score[32] = "";  // empty: no match ran
    const slam::MatchMeasure& m = a.measured;
    if (!std::isnan(m.score)) std::snprintf(score, sizeof(score), "%.4f", m.score);
    char ambiguity[32] = "";
    if (!std::isnan(m.ambiguity)) std::snprintf(ambiguity, sizeof(ambiguity), "%.4f", m.ambiguity);
    std::snprintf(line, sizeof(line), "%d,%lld,%s,%d,%lld,%.4f,%.5f,%s,%s,%d,%s\n", r.obs,
                  static_cast<long long>(a.current), search, a.candidates,
                  static_cast<long long>(a.old), a.window_m, a.window_rad, score, outcome,
                  a.accepted, ambiguity);
    text += line;
  }
  io::WriteFileAtomically(path, text);
}

}  // namespace lifelong::eval
