#include "pose_correction/pose_graph.hpp"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>

namespace slam::correction {
namespace {

// Angle folded into [-pi, pi) for plain doubles and Ceres jets alike (floor has zero derivative, so
// the jet's derivative passes through unchanged).
template <typename T>
T wrap_residual_angle(const T& a) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  using std::floor;
  return a - two_pi * floor((a + std::numbers::pi) / two_pi);
}

// Upper-triangular U with U^T U = information, so |U e|^2 is the Mahalanobis cost of e; nullopt when
// the information is not finite, not symmetric or not positive definite.
std::optional<Eigen::Matrix3d> sqrt_information(const Eigen::Matrix3d& information) {
  if (!information.allFinite()) return std::nullopt;
  const double scale = information.cwiseAbs().maxCoeff();
  if (!((information - information.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * scale)) return std::nullopt;
  const Eigen::LLT<Eigen::Matrix3d> llt(information);
  if (llt.info() != Eigen::Success) return std::nullopt;
  return Eigen::Matrix3d{llt.matrixU()};
}

// A relative edge: residual = U [R(theta_from)^T (t_to - t_from) - t_meas; wrap(theta_to - theta_from
// - theta_meas)].
struct RelativeCost {
  Pose measurement;
  Eigen::Matrix3d sqrt_info;

  template <typename T>
  bool operator()(const T* from, const T* to, T* residual) const {
    using std::cos;
    using std::sin;
    const T dx = to[0] - from[0], dy = to[1] - from[1];
    const T c = cos(from[2]), s = sin(from[2]);
    Eigen::Matrix<T, 3, 1> error;
    error << c * dx + s * dy - measurement.x, -s * dx + c * dy - measurement.y,
        wrap_residual_angle(to[2] - from[2] - measurement.theta);
    Eigen::Map<Eigen::Matrix<T, 3, 1>>{residual} = sqrt_info.cast<T>() * error;
    return true;
  }
};

// A prior: residual = U [t - t_meas; wrap(theta - theta_meas)].
struct PriorCost {
  Pose measurement;
  Eigen::Matrix3d sqrt_info;

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    Eigen::Matrix<T, 3, 1> error;
    error << pose[0] - measurement.x, pose[1] - measurement.y,
        wrap_residual_angle(pose[2] - measurement.theta);
    Eigen::Map<Eigen::Matrix<T, 3, 1>>{residual} = sqrt_info.cast<T>() * error;
    return true;
  }
};

// A heading alone: residual = sqrt(information) wrap(theta - theta_meas).
struct HeadingCost {
  double theta;
  double sqrt_info;

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    residual[0] = sqrt_info * wrap_residual_angle(pose[2] - theta);
    return true;
  }
};

// Sparse Cholesky of the normal equations when Ceres was built with a sparse library (Debian's has
// SuiteSparse), else Eigen's sparse Cholesky, else dense (slow beyond a few hundred nodes).
void choose_linear_solver(ceres::Solver::Options& options) {
  for (const auto library : {ceres::SUITE_SPARSE, ceres::EIGEN_SPARSE}) {
    if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(library)) {
      options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      options.sparse_linear_algebra_library_type = library;
      return;
    }
  }
  options.linear_solver_type = ceres::DENSE_QR;
}

// Stops the solve once the caller's cancel flag is set.
class CancelCallback : public ceres::IterationCallback {
 public:
  explicit CancelCallback(const std::atomic<bool>& cancel) : cancel_(cancel) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return cancel_.load(std::memory_order_relaxed) ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::atomic<bool>& cancel_;
};

std::string node_name(NodeId id) {
  return "node " + std::to_string(id);
}

}  // namespace

std::optional<size_t> PoseGraph::index_of(NodeId id) const {
  const auto it = index_.find(id);
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

Status PoseGraph::add_node(NodeId id, const Pose& estimate, bool fixed) {
  if (index_.contains(id)) return Error{node_name(id) + " already exists"};
  if (!is_finite(estimate)) return Error{node_name(id) + ": estimate is not finite"};
  index_.emplace(id, ids_.size());
  ids_.push_back(id);
  poses_.insert(poses_.end(), {estimate.x, estimate.y, wrap_angle(estimate.theta)});
  fixed_.push_back(fixed ? 1 : 0);
  return {};
}

Status PoseGraph::add_edge(const GraphEdge& edge) {
  if (!index_.contains(edge.from)) return Error{"edge from unknown " + node_name(edge.from)};
  if (edge.kind == EdgeKind::Heading) {
    const double information = edge.information(2, 2);
    if (!std::isfinite(edge.measurement.theta)) return Error{"edge measurement is not finite"};
    if (!(std::isfinite(information) && information > 0.0))
      return Error{"heading information is not positive"};
    edges_.push_back(edge);
    return {};
  }
  if (edge.kind != EdgeKind::Prior) {
    if (!index_.contains(edge.to)) return Error{"edge to unknown " + node_name(edge.to)};
    if (edge.from == edge.to) return Error{"relative edge joins " + node_name(edge.from) + " to itself"};
  }
  if (!is_finite(edge.measurement)) return Error{"edge measurement is not finite"};
  if (!sqrt_information(edge.information)) {
    return Error{"edge information is not symmetric positive definite"};
  }
  edges_.push_back(edge);
  return {};
}

Status PoseGraph::set_fixed(NodeId id, bool fixed) {
  const auto index = index_of(id);
  if (!index) return Error{"unknown " + node_name(id)};
  fixed_[*index] = fixed ? 1 : 0;
  return {};
}

std::optional<Pose> PoseGraph::estimate(NodeId id) const {
  const auto index = index_of(id);
  if (!index) return std::nullopt;
  const double* p = &poses_[3 * *index];
  return Pose{p[0], p[1], p[2]};
}

std::vector<NodeEstimate> PoseGraph::estimates() const {
  std::vector<NodeEstimate> out;
  out.reserve(ids_.size());
  for (size_t i = 0; i < ids_.size(); ++i) {
    out.push_back({ids_[i], {poses_[3 * i], poses_[3 * i + 1], poses_[3 * i + 2]}});
  }
  return out;
}

Result<OptimiseStats> PoseGraph::optimise(const OptimiseOptions& options) {
  if (options.max_iterations <= 0) return Error{"max_iterations must be positive"};
  if (!(options.loop_closure_loss_scale > 0.0)) return Error{"loop_closure_loss_scale must be positive"};
  OptimiseStats stats;
  if (ids_.empty()) {
    stats.converged = true;
    return stats;
  }

  // Solve on a copy so a failed solve leaves the estimates untouched.
  std::vector<double> solution = poses_;
  ceres::Problem problem;
  // One loss shared by every loop closure; the problem owns and deletes it once.
  ceres::LossFunction* closure_loss =
      options.robust_loop_closures ? new ceres::CauchyLoss(options.loop_closure_loss_scale) : nullptr;
  bool closure_loss_used = false;
  bool anchored = false;
  for (const GraphEdge& edge : edges_) {
    double* from = &solution[3 * index_.at(edge.from)];
    if (edge.kind == EdgeKind::Heading) {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<HeadingCost, 1, 3>(new HeadingCost{
                                   edge.measurement.theta, std::sqrt(edge.information(2, 2))}),
                               nullptr, from);
      continue;
    }
    const Eigen::Matrix3d sqrt_info = *sqrt_information(edge.information);  // checked in add_edge
    if (edge.kind == EdgeKind::Prior) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<PriorCost, 3, 3>(new PriorCost{edge.measurement, sqrt_info}),
          nullptr, from);
      anchored = true;
      continue;
    }
    double* to = &solution[3 * index_.at(edge.to)];
    ceres::LossFunction* loss = nullptr;
    if (edge.kind == EdgeKind::LoopClosure && closure_loss != nullptr) {
      loss = closure_loss;
      closure_loss_used = true;
    }
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<RelativeCost, 3, 3, 3>(new RelativeCost{edge.measurement, sqrt_info}),
        loss, from, to);
  }
  if (!closure_loss_used) delete closure_loss;

  for (size_t i = 0; i < ids_.size(); ++i) {
    double* block = &solution[3 * i];
    // A node no edge touches is not a parameter of the problem; it keeps its estimate.
    if (!problem.HasParameterBlock(block)) continue;
    if (fixed_[i] != 0) {
      problem.SetParameterBlockConstant(block);
      anchored = true;
    }
  }
  if (!anchored && problem.HasParameterBlock(solution.data()))
    problem.SetParameterBlockConstant(solution.data());

  ceres::Solver::Options solver_options;
  choose_linear_solver(solver_options);
  // Dogleg reaches the same minimum as Levenberg-Marquardt in about half the iterations on drifted
  // fleet graphs (bench_slam_graph: 7 against 13).
  solver_options.trust_region_strategy_type = ceres::DOGLEG;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  std::optional<CancelCallback> cancel_callback;
  if (options.cancel != nullptr) {
    cancel_callback.emplace(*options.cancel);
    solver_options.callbacks.push_back(&*cancel_callback);
  }
  ceres::Solver::Summary summary;
  if (problem.NumResidualBlocks() > 0) {
    ceres::Solve(solver_options, &problem, &summary);
    if (summary.termination_type == ceres::USER_FAILURE) return Error{"pose graph solve cancelled"};
    if (!summary.IsSolutionUsable()) return Error{"pose graph solve failed: " + summary.message};
    stats.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
    stats.initial_cost = summary.initial_cost;
    stats.final_cost = summary.final_cost;
    stats.converged = summary.termination_type == ceres::CONVERGENCE;
  } else {
    stats.converged = true;
  }

  for (size_t i = 0; i < ids_.size(); ++i) {
    double* p = &solution[3 * i];
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) {
      return Error{"pose graph solve gave a non-finite estimate for " + node_name(ids_[i])};
    }
    p[2] = wrap_angle(p[2]);
    stats.max_node_shift_m =
        std::max(stats.max_node_shift_m, std::hypot(p[0] - poses_[3 * i], p[1] - poses_[3 * i + 1]));
  }
  poses_ = std::move(solution);
  return stats;
}

Eigen::Matrix3d compose_covariance(const Pose& a, const Eigen::Matrix3d& ca, const Pose& b,
                                   const Eigen::Matrix3d& cb) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  // t = t_a + R(theta_a) t_b, theta = theta_a + theta_b.
  Eigen::Matrix3d ja = Eigen::Matrix3d::Identity();
  ja(0, 2) = -s * b.x - c * b.y;
  ja(1, 2) = c * b.x - s * b.y;
  Eigen::Matrix3d jb = Eigen::Matrix3d::Identity();
  jb.topLeftCorner<2, 2>() << c, -s, s, c;
  return ja * ca * ja.transpose() + jb * cb * jb.transpose();
}

Result<UncertainPose> accumulate_chain(std::span<const GraphEdge> edges) {
  UncertainPose chain;
  for (size_t i = 0; i < edges.size(); ++i) {
    const GraphEdge& edge = edges[i];
    if (edge.kind == EdgeKind::Prior || edge.kind == EdgeKind::Heading) {
      return Error{"chain edge " + std::to_string(i) + " is unary"};
    }
    if (i > 0 && edges[i - 1].to != edge.from) {
      return Error{"chain breaks at edge " + std::to_string(i) + ": " + node_name(edges[i - 1].to) +
                   " then " + node_name(edge.from)};
    }
    if (!sqrt_information(edge.information)) {
      return Error{"chain edge " + std::to_string(i) + ": information is not symmetric positive definite"};
    }
    const Eigen::Matrix3d covariance = edge.information.inverse();
    chain.covariance = compose_covariance(chain.pose, chain.covariance, edge.measurement, covariance);
    chain.pose = chain.pose.compose(edge.measurement);
  }
  return chain;
}

bool ConsistencyCheck::accepts(const Pose& predicted_relative, const Pose& measured_relative,
                               const Eigen::Matrix3d& uncertainty) const {
  if (!is_finite(predicted_relative) || !is_finite(measured_relative) || !uncertainty.allFinite())
    return false;
  const Eigen::LLT<Eigen::Matrix3d> llt(0.5 * (uncertainty + uncertainty.transpose()));
  if (llt.info() != Eigen::Success) return false;
  const Pose difference = predicted_relative.inverse().compose(measured_relative);
  const Eigen::Vector3d error{difference.x, difference.y, wrap_angle(difference.theta)};
  const double mahalanobis_squared = error.dot(llt.solve(error));
  return mahalanobis_squared <= chi2_bound;
}

}  // namespace slam::correction
