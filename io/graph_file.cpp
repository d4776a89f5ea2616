#include "io/graph_file.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "io/atomic_file.hpp"
#include "sensor/input_bounds.hpp"
#include "sensor/input_error.hpp"

namespace lifelong::io {
namespace {

constexpr long long kMaxId = 1LL << 62;

// Tokens of one line, each parsed with the field name that goes into InputError.
class LineReader {
 public:
  LineReader(const std::string& file, int line, const std::string& text)
      : file_(file), line_(line), in_(text) {}

  int line() const { return line_; }
  std::size_t Length() const { return in_.str().size(); }
  std::string Tag() {
    std::string tag;
    in_ >> tag;
    return tag;
  }
  double Number(const std::string& field) {
    const std::string token = Token(field);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(token.c_str(), &end);
    if (*end != '\0' || errno == ERANGE || !std::isfinite(v))
      Fail(field, "not a finite number: '" + token + "'");
    return v;
  }
  /// A number of magnitude at most `bound` (sensor/input_bounds.hpp).
  double Bounded(const std::string& field, double bound) {
    const double v = Number(field);
    if (std::abs(v) > bound) {
      std::ostringstream what;
      what << v << " is beyond " << bound << ": corrupt, not data";
      Fail(field, what.str());
    }
    return v;
  }
  NodeId Id(const std::string& field) {
    const std::string token = Token(field);
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(token.c_str(), &end, 10);
    if (*end != '\0' || errno == ERANGE) Fail(field, "not an integer id: '" + token + "'");
    // Leaves room for id + 1 and id - 1 (odometry edges, chaining) without overflow.
    if (v > kMaxId || v < -kMaxId) Fail(field, "id out of range [-2^62, 2^62]: '" + token + "'");
    return v;
  }
  void ExpectEnd() {
    std::string extra;
    if (in_ >> extra) Fail("", "unexpected extra token '" + extra + "'");
  }
  [[noreturn]] void Fail(const std::string& field, const std::string& what) const {
    throw InputError(file_, line_, field, what);
  }

 private:
  std::string Token(const std::string& field) {
    std::string token;
    if (!(in_ >> token)) Fail(field, "missing (truncated line)");
    return token;
  }
  const std::string& file_;
  int line_;
  std::istringstream in_;
};

// Information upper triangle in the file's order -> symmetric 3x3, checked SPD.
Eigen::Matrix3d ReadInformation(LineReader* r, GraphFormat format) {
  // Index pairs (row, col) in reading order.
  static const int kG2o[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
  static const int kToro[6][2] = {{0, 0}, {0, 1}, {1, 1}, {2, 2}, {0, 2}, {1, 2}};
  const auto& order = format == GraphFormat::kG2o ? kG2o : kToro;
  Eigen::Matrix3d info;
  for (const auto& rc : order) {
    const std::string field = "I" + std::to_string(rc[0] + 1) + std::to_string(rc[1] + 1);
    info(rc[0], rc[1]) = info(rc[1], rc[0]) = r->Bounded(field, kMaxInformation);
  }
  if (info.llt().info() != Eigen::Success) {
    r->Fail("information", "information matrix is not positive definite");
  }
  return info;
}

Pose2 ReadPose(LineReader* r, const std::string& prefix) {
  const double x = r->Bounded(prefix + "x", kMaxCoordinateM);
  const double y = r->Bounded(prefix + "y", kMaxCoordinateM);
  return {x, y, r->Number(prefix + "theta")};
}

struct PendingEdge {
  PoseEdge edge;
  int line;
};
struct PendingClique {
  CliqueFactor clique;
  int line;
};

struct Parsed {
  GraphFile result;
  std::set<NodeId> nodes;  ///< result.factors.nodes, for lookups
  std::vector<PendingEdge> edges;
  std::vector<PendingClique> cliques;
  bool has_format = false;
};

void SetFormat(Parsed* p, GraphFormat format, LineReader* r) {
  if (p->has_format && p->result.format != format)
    r->Fail("tag", "file mixes g2o and TORO records");
  p->result.format = format;
  p->has_format = true;
}

void ReadVertex(Parsed* p, LineReader* r) {
  const NodeId id = r->Id("id");
  const Pose2 pose = ReadPose(r, "");
  r->ExpectEnd();
  if (!p->nodes.insert(id).second) r->Fail("id", "duplicate vertex " + std::to_string(id));
  p->result.factors.nodes.push_back(id);
  p->result.values[id] = pose;
}

void ReadEdge(Parsed* p, LineReader* r) {
  PoseEdge e;
  e.from = r->Id("from");
  e.to = r->Id("to");
  e.T_from_to = ReadPose(r, "d");
  e.information = ReadInformation(r, p->result.format);
  r->ExpectEnd();
  if (e.from == e.to) r->Fail("to", "edge from a vertex to itself");
  e.kind = e.to == e.from + 1 ? EdgeKind::kOdometry : EdgeKind::kLoop;
  e.robust = e.kind == EdgeKind::kLoop;
  p->edges.push_back({e, r->line()});
}

void ReadClique(Parsed* p, LineReader* r) {
  const NodeId m = r->Id("size");
  if (m < 2) r->Fail("size", "clique size must be at least 2");
  // Every token takes at least two characters of the line, so a size the record cannot hold
  // is refused before anything of its size is allocated.
  const double tokens = static_cast<double>(m) * 4.0 - 3.0 +
                        4.5 * static_cast<double>(m - 1) * static_cast<double>(m - 1) +
                        1.5 * static_cast<double>(m - 1);
  if (2.0 * tokens > static_cast<double>(r->Length()) + 1.0) {
    r->Fail("size", "the record is too short for a clique of " + std::to_string(m) + " nodes");
  }
  CliqueFactor c;
  for (NodeId k = 0; k < m; ++k) c.nodes.push_back(r->Id("node"));
  if (std::set<NodeId>(c.nodes.begin(), c.nodes.end()).size() != c.nodes.size()) {
    r->Fail("node", "clique names a node twice");
  }
  for (NodeId k = 1; k < m; ++k) c.T_root_node.push_back(ReadPose(r, "d"));
  const Eigen::Index d = 3 * (m - 1);
  c.information.resize(d, d);
  for (Eigen::Index i = 0; i < d; ++i) {
    for (Eigen::Index j = i; j < d; ++j) {
      c.information(i, j) = c.information(j, i) = r->Bounded("I", kMaxInformation);
    }
  }
  r->ExpectEnd();
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(c.information, Eigen::EigenvaluesOnly)
          .eigenvalues();
  const double max_ev = ev.cwiseAbs().maxCoeff();
  if (ev.minCoeff() < -1e-9 * max_ev) {
    r->Fail("information", "clique information is not positive semidefinite");
  }
  p->cliques.push_back({c, r->line()});
}

void ReadLine(Parsed* p, LineReader* r) {
  const std::string tag = r->Tag();
  if (tag.empty() || tag[0] == '#') return;
  if (tag == "VERTEX_SE2" || tag == "VERTEX2") {
    SetFormat(p, tag == "VERTEX2" ? GraphFormat::kToro : GraphFormat::kG2o, r);
    ReadVertex(p, r);
  } else if (tag == "EDGE_SE2" || tag == "EDGE2") {
    SetFormat(p, tag == "EDGE2" ? GraphFormat::kToro : GraphFormat::kG2o, r);
    ReadEdge(p, r);
  } else if (tag == "LIFELONG_CLIQUE_SE2") {
    SetFormat(p, GraphFormat::kG2o, r);
    ReadClique(p, r);
  } else if (tag == "FIX") {
    SetFormat(p, GraphFormat::kG2o, r);
    p->result.fixed.push_back(r->Id("id"));
  } else {
    r->Fail("tag", "unsupported record '" + tag + "'");
  }
}

// Initial guess for an edges-only file: origin at the smallest id, compose i -> i+1
// odometry, then spread over any edge touching a placed node until nothing changes.
void ChainValues(GraphFile* g, const std::set<NodeId>& nodes) {
  Values& v = g->values;
  const std::vector<NodeId> ids(nodes.begin(), nodes.end());
  if (ids.empty()) return;
  v[ids.front()] = Pose2();
  std::map<NodeId, const PoseEdge*> odometry;
  for (const PoseEdge& e : g->factors.edges) {
    if (e.to == e.from + 1) odometry.emplace(e.from, &e);
  }
  for (NodeId id : ids) {
    auto it = odometry.find(id - 1);
    if (!v.count(id) && it != odometry.end() && v.count(id - 1)) {
      v[id] = v[id - 1] * it->second->T_from_to;
    }
  }
  // Breadth-first over the edges from every node placed so far, then from the lowest id of
  // each piece still unplaced (at the origin): linear in the edges, whatever their order.
  std::map<NodeId, std::vector<const PoseEdge*>> incident;
  for (const PoseEdge& e : g->factors.edges) {
    incident[e.from].push_back(&e);
    incident[e.to].push_back(&e);
  }
  std::deque<NodeId> queue;
  for (const auto& [id, unused] : v) queue.push_back(id);
  const auto spread = [&]() {
    while (!queue.empty()) {
      const NodeId u = queue.front();
      queue.pop_front();
      for (const PoseEdge* e : incident[u]) {
        const NodeId w = e->from == u ? e->to : e->from;
        if (v.count(w)) continue;
        v[w] = e->from == u ? v.at(u) * e->T_from_to : v.at(u) * e->T_from_to.Inverse();
        queue.push_back(w);
      }
    }
  };
  spread();
  for (NodeId id : ids) {
    if (v.count(id)) continue;
    v[id] = Pose2();  // a piece not connected to the first node starts at the origin
    queue.push_back(id);
    spread();
  }
}

void AddFactors(Parsed* p, const std::string& name) {
  GraphFile& g = p->result;
  const bool no_vertices = p->nodes.empty();
  for (const PendingEdge& pe : p->edges) {
    for (NodeId id : {pe.edge.from, pe.edge.to}) {
      if (p->nodes.count(id)) continue;
      if (!no_vertices)
        throw InputError(name, pe.line, "id", "edge to unknown vertex " + std::to_string(id));
      p->nodes.insert(id);
      g.factors.nodes.push_back(id);
    }
    g.factors.edges.push_back(pe.edge);
  }
  for (const PendingClique& pc : p->cliques) {
    for (NodeId id : pc.clique.nodes) {
      if (!p->nodes.count(id)) throw InputError(name, pc.line, "node", "clique on unknown vertex");
    }
    g.factors.cliques.push_back(pc.clique);
  }
  if (no_vertices && !p->nodes.empty()) {
    ChainValues(&g, p->nodes);
    g.values_from_edges = true;
  }
}

void WritePose(std::ostream& out, const Pose2& p) {
  out << ' ' << p.x << ' ' << p.y << ' ' << p.theta;
}

const Pose2& ValueOf(const Values& values, NodeId id) {
  auto it = values.find(id);
  if (it == values.end())
    throw std::invalid_argument("WriteG2o: no value for node " + std::to_string(id));
  return it->second;
}

}  // namespace

GraphFile ParseGraph(std::istream& in, const std::string& name) {
  Parsed p;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    LineReader reader(name, line, text);
    ReadLine(&p, &reader);
  }
  AddFactors(&p, name);
  return std::move(p.result);
}

GraphFile ReadGraphFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open graph file");
  return ParseGraph(in, path);
}

void WriteG2o(std::ostream& out, const PoseFactors& graph, const Values& values) {
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (NodeId id : graph.nodes) {
    out << "VERTEX_SE2 " << id;
    WritePose(out, ValueOf(values, id));
    out << '\n';
  }
  for (const PoseEdge& e : graph.edges) {
    const Eigen::Matrix3d& I = e.information;
    out << "EDGE_SE2 " << e.from << ' ' << e.to;
    WritePose(out, e.T_from_to);
    out << ' ' << I(0, 0) << ' ' << I(0, 1) << ' ' << I(0, 2) << ' ' << I(1, 1) << ' ' << I(1, 2)
        << ' ' << I(2, 2) << '\n';
  }
  for (const CliqueFactor& c : graph.cliques) {
    out << "LIFELONG_CLIQUE_SE2 " << c.nodes.size();
    for (NodeId id : c.nodes) out << ' ' << id;
    for (const Pose2& z : c.T_root_node) WritePose(out, z);
    for (Eigen::Index i = 0; i < c.information.rows(); ++i) {
      for (Eigen::Index j = i; j < c.information.cols(); ++j) out << ' ' << c.information(i, j);
    }
    out << '\n';
  }
}

void WriteG2o(const std::string& path, const PoseFactors& graph, const Values& values) {
  std::ostringstream out;
  WriteG2o(out, graph, values);
  WriteFileAtomically(path, out.str());
}

void WriteToro(std::ostream& out, const PoseFactors& graph, const Values& values) {
  if (!graph.cliques.empty())
    throw std::invalid_argument("WriteToro: clique factors have no TORO form");
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (NodeId id : graph.nodes) {
    out << "VERTEX2 " << id;
    WritePose(out, ValueOf(values, id));
    out << '\n';
  }
  for (const PoseEdge& e : graph.edges) {
    const Eigen::Matrix3d& I = e.information;
    out << "EDGE2 " << e.from << ' ' << e.to;
    WritePose(out, e.T_from_to);
    out << ' ' << I(0, 0) << ' ' << I(0, 1) << ' ' << I(1, 1) << ' ' << I(2, 2) << ' ' << I(0, 2)
        << ' ' << I(1, 2) << '\n';
  }
}

}  // namespace lifelong::io
