// Pose-graph files: g2o (Kuemmerle et al. 2011) and TORO (Grisetti et al. 2007), 2D only.
//   g2o : VERTEX_SE2 id x y th
//         EDGE_SE2 i j dx dy dth I11 I12 I13 I22 I23 I33
//   TORO: VERTEX2 id x y th
//         EDGE2 i j dx dy dth I11 I12 I22 I33 I13 I23      (note the information order)
// Edge measurements are Z = T_i_j, the information upper triangles in (x, y, theta) order.
// Also read: `FIX id` (g2o), comments (`#`), blank lines. Our dense marginal cliques
// (CliqueFactor) have no g2o type; they are written as an extension record
//   LIFELONG_CLIQUE_SE2 m id_root id_1..id_{m-1} (x y th)*(m-1) upper-triangle(3(m-1))
// which g2o's own loader skips with a warning and ReadGraphFile reads back. Its error is
// e_j = t2v(Z_j^-1 X_root^-1 X_{id_j}) stacked over j, the root-shifted form of a generic
// linear constraint (Carlevaris-Bianco et al. 2014), so GLC factors (slam/marginal/glc.hpp) need no
// other record: a low-rank GLC factor is written with its positive semidefinite information
// (rank below 3(m-1)), and a ternary GLC conditional is a record with m = 3.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "types/pose_factors.hpp"

namespace lifelong::io {

enum class GraphFormat { kG2o, kToro };

/// A graph file's content as plain data; slam::PoseGraph::FromFactors makes it a graph.
struct GraphFile {
  PoseFactors factors;  ///< vertices in file order, then edges and cliques in file order
  Values values;
  GraphFormat format = GraphFormat::kG2o;
  /// True when the file had edges but no vertices and `values` were built by chaining the
  /// odometry edges i -> i+1 (then any remaining edge) from the smallest id at the origin.
  bool values_from_edges = false;
  std::vector<NodeId> fixed;  ///< ids named by g2o FIX lines
};

/// Reads a g2o or TORO file, the format told by its records. Edges j == i + 1 become
/// EdgeKind::kOdometry, others kLoop with robust = true. Throws lifelong::InputError
/// (file, line, field) on unreadable files, corrupt or truncated lines, unknown records,
/// duplicate vertices, edges to unknown vertices, ids beyond +-2^62, cliques naming a node
/// twice and non-positive-definite information.
GraphFile ReadGraphFile(const std::string& path);
/// Same, from a stream; `name` is used in error messages.
GraphFile ParseGraph(std::istream& in, const std::string& name);

/// Writes every node (values must hold each) in the order of `graph.nodes`, then every edge
/// and clique factor, in g2o format (slam::PoseGraph::Factors() lists the nodes ascending).
/// The file is written atomically (io/atomic_file.hpp); throws lifelong::InputError when it
/// cannot be written.
void WriteG2o(const std::string& path, const PoseFactors& graph, const Values& values);
void WriteG2o(std::ostream& out, const PoseFactors& graph, const Values& values);
/// TORO format; clique factors have no TORO form and throw std::invalid_argument.
void WriteToro(std::ostream& out, const PoseFactors& graph, const Values& values);

}  // namespace lifelong::io
