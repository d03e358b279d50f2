// PoseGraph2D (pose_graph.h): SE(2) nodes and relative-pose edges, optimised by Ceres with
// Levenberg-Marquardt and a sparse Cholesky solver.
#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/slam/pose_graph.h"

namespace adaptive_perception::slam {

namespace {
struct EdgeCost {
  EdgeCost(const math::SE2& z, const Eigen::Matrix3d& sqrt_info) : z_(z), sqrt_info_(sqrt_info) {}
  template <typename T>
  bool operator()(const T* xi, const T* xj, T* r) const {
    using std::atan2;
    using std::cos;
    using std::sin;
    const T c = cos(xi[2]), s = sin(xi[2]);
    const T dx = xj[0] - xi[0], dy = xj[1] - xi[1];
    const T e0 = c * dx + s * dy - T(z_.x_m);
    const T e1 = -s * dx + c * dy - T(z_.y_m);
    const T a = xj[2] - xi[2] - T(z_.yaw_rad);
    const T e2 = atan2(sin(a), cos(a));
    for (int k = 0; k < 3; ++k)
      r[k] = T(sqrt_info_(k, 0)) * e0 + T(sqrt_info_(k, 1)) * e1 + T(sqrt_info_(k, 2)) * e2;
    return true;
  }
  math::SE2 z_;
  Eigen::Matrix3d sqrt_info_;
};
}  // namespace

int PoseGraph2D::addNode(const math::SE2& x) {
  x_.push_back({x.x_m, x.y_m, x.yaw_rad});
  return numNodes() - 1;
}

void PoseGraph2D::addEdge(int i, int j, const math::SE2& z, const Eigen::Matrix3d& info, bool loop,
                          bool robust) {
  if (i < 0 || j < 0 || i >= numNodes() || j >= numNodes() || i == j)
    throw std::invalid_argument("PoseGraph2D::addEdge: unknown node");
  const Eigen::LLT<Eigen::Matrix3d> llt(info);
  if (llt.info() != Eigen::Success || !info.allFinite())
    throw std::invalid_argument("PoseGraph2D::addEdge: information not positive definite");
  edges_.push_back({i, j, z, Eigen::Matrix3d(llt.matrixU()), loop, robust});
}

void PoseGraph2D::addRobustChainEdge(int i, int j, const math::SE2& z, const Eigen::Matrix3d& info,
                                     double huber_scale) {
  if (!(huber_scale > 0.0) || !std::isfinite(huber_scale))
    throw std::invalid_argument("PoseGraph2D::addRobustChainEdge: huber_scale must be > 0");
  addEdge(i, j, z, info, false, false);
  edges_.back().huber_scale = huber_scale;
}

int PoseGraph2D::numLoopEdges() const {
  return static_cast<int>(
      std::count_if(edges_.begin(), edges_.end(), [](const Edge& e) { return e.loop; }));
}

math::SE2 PoseGraph2D::node(int i) const { return math::SE2(x_.at(i)[0], x_[i][1], x_[i][2]); }

double PoseGraph2D::optimize(int max_iterations) {
  if (x_.empty()) return 0.0;
  ceres::Problem problem;
  for (const Edge& e : edges_) {
    ceres::LossFunction* loss = nullptr;
    if (e.loop && e.robust)
      loss = new ceres::CauchyLoss(1.0);
    else if (e.huber_scale > 0.0)
      loss = new ceres::HuberLoss(e.huber_scale);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<EdgeCost, 3, 3, 3>(new EdgeCost(e.z, e.sqrt_info)), loss,
        x_[e.i].data(), x_[e.j].data());
  }
  if (!problem.HasParameterBlock(x_[0].data())) return 0.0;
  problem.SetParameterBlockConstant(x_[0].data());
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-12;  // the defaults stop about 1e-4 m short of the optimum
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  for (auto& x : x_) x[2] = math::wrapAngle(x[2]);
  return summary.final_cost;
}

}  // namespace adaptive_perception::slam
