#pragma once
// The pose graph: one node per keyframe (its pose in the map frame), relative-pose edges between
// keyframes (consecutive ones of a robot: odometry refined by matching; loop closures: a keyframe
// matched against older keyframes), unary prior edges (an operator's initial pose, the first
// keyframe of a segment) and unary heading edges (the walls' directions, wall_axes.hpp). Optimised with
// Ceres; loop-closure edges carry a robust loss so one bad closure that slipped through the consistency check
// cannot drag the graph.
#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"

namespace slam::correction {

using NodeId = uint64_t;

enum class EdgeKind : uint8_t { Sequential, LoopClosure, Prior, Heading };

struct GraphEdge {
  EdgeKind kind = EdgeKind::Sequential;
  NodeId from = 0;   // Prior, Heading: the node constrained
  NodeId to = 0;     // unused for Prior and Heading
  Pose measurement;  // relative: from^-1 ∘ to; Prior: the node's pose in the map; Heading: theta only
  // Inverse covariance of (x, y, theta); a Heading edge reads only its (2, 2) entry.
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
};

struct OptimiseOptions {
  int max_iterations = 50;
  // Relative change of the cost below which Ceres stops: the graph moves by far less than a grid
  // cell once the cost changes by this little.
  double function_tolerance = 1e-6;
  // Cauchy loss on loop closures (scale in whitened units: residuals beyond ~1 sigma are damped).
  // Off only to compare against a plain quadratic loss.
  bool robust_loop_closures = true;
  double loop_closure_loss_scale = 1.0;
  // When given and set, the solve stops at its next iteration and optimise() reports an error.
  const std::atomic<bool>* cancel = nullptr;
};

struct OptimiseStats {
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  double max_node_shift_m = 0.0;  // largest position change of any node
  bool converged = false;
};

struct NodeEstimate {
  NodeId id = 0;
  Pose pose;
  bool operator==(const NodeEstimate&) const = default;
};

class PoseGraph {
 public:
  // Adds a node with its initial estimate; ids are unique (an existing id is an error), the pose
  // must be finite. A fixed node keeps its estimate through optimisation.
  Status add_node(NodeId id, const Pose& estimate, bool fixed = false);
  // Both ends must exist (a relative edge joins two distinct nodes); the measurement must be finite
  // and the information symmetric positive definite.
  Status add_edge(const GraphEdge& edge);
  Status set_fixed(NodeId id, bool fixed);

  // Runs Ceres over every node and edge and, on success, updates the estimates (on failure they
  // stay as they were). Loop closures use a Cauchy loss. A graph with neither a fixed node nor a
  // prior would float freely; then the first node added holds still.
  Result<OptimiseStats> optimise(const OptimiseOptions& options = {});

  // nullopt for an unknown id.
  std::optional<Pose> estimate(NodeId id) const;
  // Every node's estimate in the order the nodes were added.
  std::vector<NodeEstimate> estimates() const;
  size_t node_count() const { return ids_.size(); }
  size_t edge_count() const { return edges_.size(); }

 private:
  std::optional<size_t> index_of(NodeId id) const;

  std::vector<NodeId> ids_;
  std::vector<double> poses_;  // x, y, theta per node, in the order of ids_ (Ceres' parameter blocks)
  std::vector<uint8_t> fixed_;
  std::unordered_map<NodeId, size_t> index_;
  std::vector<GraphEdge> edges_;
};

// A relative pose with the covariance of its (x, y, theta).
struct UncertainPose {
  Pose pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

// Covariance of a ∘ b for independent a and b, to first order: J_a ca J_a^T + J_b cb J_b^T with the
// Jacobians of compose at (a, b).
Eigen::Matrix3d compose_covariance(const Pose& a, const Eigen::Matrix3d& ca, const Pose& b,
                                   const Eigen::Matrix3d& cb);

// The relative pose and its covariance accumulated along a chain of relative edges, each edge's
// covariance being the inverse of its information; consecutive edges must share a node
// (edges[i].to == edges[i + 1].from). An empty chain is the identity with zero covariance.
Result<UncertainPose> accumulate_chain(std::span<const GraphEdge> edges);

// Whether a candidate loop closure agrees with what the graph already believes: the Mahalanobis
// distance of (predicted^-1 ∘ measured) under `uncertainty` (the covariance accumulated along the
// chain since the two keyframes were last tied together, plus the match's) is below the
// chi-square bound (3 dof). A closure that fails it is rejected: a wrong closure is worse than none;
// so is one judged under a non-finite or not positive definite uncertainty.
struct ConsistencyCheck {
  double chi2_bound = 11.34;  // 99 % for 3 dof
  bool accepts(const Pose& predicted_relative, const Pose& measured_relative,
               const Eigen::Matrix3d& uncertainty) const;
};

}  // namespace slam::correction
