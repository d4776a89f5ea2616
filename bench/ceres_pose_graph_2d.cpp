// A yardstick for `lifelong optimize`: the same SE(2) pose-graph problem solved by Ceres,
// as a whole program (read the g2o file, build the problem, solve, print). Built only when
// Ceres is found (bench/CMakeLists.txt); it shares no code with lifelong.
//
//   ceres_pose_graph_2d GRAPH.g2o
//
// prints vertices, edges, initial_chi2, final_chi2, iterations and solve_time_s, as
// `lifelong optimize` does. The problem is ours (DESIGN.md, slam/graph/se2.hpp):
//   - one parameter block (x, y, theta) per VERTEX_SE2, updated additively with theta
//     wrapped into [-pi, pi) (as our optimizer and g2o's VertexSE2);
//   - per EDGE_SE2 the error e = t2v(Z^-1 (Xi^-1 Xj)):
//       e_t     = R(th_z)^T (R(th_i)^T (t_j - t_i) - t_z)
//       e_theta = wrap(th_j - th_i - th_z)
//     whitened as r = U e with U^T U = Omega (U upper triangular), so |r|^2 = e^T Omega e;
//   - the vertex with the smallest id held fixed; Jacobians by automatic differentiation;
//   - Levenberg-Marquardt with a sparse Cholesky of the normal equations (SuiteSparse),
//     stopping on a relative cost decrease below 1e-9 (our relative_tolerance), one thread.
// chi2 = sum e^T Omega e = 2 x Ceres' cost.
#include <ceres/ceres.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace {

constexpr double kPi = 3.14159265358979323846;

template <typename T>
T WrapAngle(const T& a) {  // into [-pi, pi)
  return a - T(2.0 * kPi) * ceres::floor((a + T(kPi)) / T(2.0 * kPi));
}

struct Edge {
  int from = 0, to = 0;
  double dx = 0.0, dy = 0.0, dtheta = 0.0;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
};

struct Graph {
  std::map<int, Eigen::Vector3d> vertices;  // id -> (x, y, theta); std::map: stable addresses
  std::vector<Edge> edges;
};

// VERTEX_SE2 id x y theta; EDGE_SE2 from to dx dy dtheta I11 I12 I13 I22 I23 I33.
Graph ReadG2o(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  Graph g;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream s(line);
    std::string tag;
    if (!(s >> tag)) continue;
    if (tag == "VERTEX_SE2") {
      int id = 0;
      Eigen::Vector3d v;
      if (!(s >> id >> v.x() >> v.y() >> v.z())) throw std::runtime_error(path + ": bad vertex");
      g.vertices[id] = v;
    } else if (tag == "EDGE_SE2") {
      Edge e;
      double i11, i12, i13, i22, i23, i33;
      if (!(s >> e.from >> e.to >> e.dx >> e.dy >> e.dtheta >> i11 >> i12 >> i13 >> i22 >> i23 >>
            i33)) {
        throw std::runtime_error(path + ":" + std::to_string(n) + ": bad edge");
      }
      e.information << i11, i12, i13, i12, i22, i23, i13, i23, i33;
      g.edges.push_back(e);
    }
  }
  return g;
}

// The whitened relative-pose error of one edge (see the header comment).
class RelativePoseError {
 public:
  explicit RelativePoseError(const Edge& edge) : dx_(edge.dx), dy_(edge.dy), dtheta_(edge.dtheta) {
    const Eigen::Matrix3d L = edge.information.llt().matrixL();
    sqrt_information_ = L.transpose();
  }

  template <typename T>
  bool operator()(const T* xi, const T* xj, T* residual) const {
    using std::cos;
    using std::sin;
    const T ci = cos(xi[2]), si = sin(xi[2]);
    const T tx = xj[0] - xi[0], ty = xj[1] - xi[1];
    const T rx = ci * tx + si * ty - T(dx_);  // R(th_i)^T (t_j - t_i) - t_z
    const T ry = -si * tx + ci * ty - T(dy_);
    const double cz = std::cos(dtheta_), sz = std::sin(dtheta_);
    Eigen::Matrix<T, 3, 1> e;
    e << T(cz) * rx + T(sz) * ry, T(-sz) * rx + T(cz) * ry, WrapAngle(xj[2] - xi[2] - T(dtheta_));
    Eigen::Map<Eigen::Matrix<T, 3, 1>> r(residual);
    r = sqrt_information_.cast<T>() * e;
    return true;
  }

 private:
  double dx_, dy_, dtheta_;
  Eigen::Matrix3d sqrt_information_;
};

// x <- x + delta with the heading wrapped; Minus is its inverse.
struct AdditiveWrappedSe2 {
  template <typename T>
  bool Plus(const T* x, const T* delta, T* out) const {
    out[0] = x[0] + delta[0];
    out[1] = x[1] + delta[1];
    out[2] = WrapAngle(x[2] + delta[2]);
    return true;
  }
  template <typename T>
  bool Minus(const T* y, const T* x, T* delta) const {
    delta[0] = y[0] - x[0];
    delta[1] = y[1] - x[1];
    delta[2] = WrapAngle(y[2] - x[2]);
    return true;
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s GRAPH.g2o\n", argv[0]);
    return 2;
  }
  try {
    Graph g = ReadG2o(argv[1]);
    if (g.vertices.empty()) throw std::runtime_error(std::string(argv[1]) + ": no vertices");
    ceres::Problem problem;
    auto* manifold = new ceres::AutoDiffManifold<AdditiveWrappedSe2, 3, 3>;  // owned by problem
    for (const Edge& e : g.edges) {
      auto* cost =
          new ceres::AutoDiffCostFunction<RelativePoseError, 3, 3, 3>(new RelativePoseError(e));
      problem.AddResidualBlock(cost, nullptr, g.vertices.at(e.from).data(),
                               g.vertices.at(e.to).data());
    }
    for (auto& [id, v] : g.vertices) {
      if (problem.HasParameterBlock(v.data())) problem.SetManifold(v.data(), manifold);
    }
    double* anchor = g.vertices.begin()->second.data();
    if (problem.HasParameterBlock(anchor)) problem.SetParameterBlockConstant(anchor);

    ceres::Solver::Options options;
    options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
    options.max_num_iterations = 100;
    options.function_tolerance = 1e-9;
    options.num_threads = 1;
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    const auto start = std::chrono::steady_clock::now();
    ceres::Solve(options, &problem, &summary);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("vertices %zu\nedges %zu\n", g.vertices.size(), g.edges.size());
    std::printf("initial_chi2 %.10g\nfinal_chi2 %.10g\n", 2.0 * summary.initial_cost,
                2.0 * summary.final_cost);
    std::printf("iterations %d\nsolve_time_s %.9f\n",
                static_cast<int>(summary.iterations.size()) - 1, seconds);
    std::printf("converged %s (%s)\n",
                summary.termination_type == ceres::CONVERGENCE ? "yes" : "no",
                summary.message.c_str());
    return summary.IsSolutionUsable() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ceres_pose_graph_2d: %s\n", e.what());
    return 2;
  }
}
