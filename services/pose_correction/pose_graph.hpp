#pragma once
// The pose graph: one node per keyframe (its pose in the map frame), relative-pose edges between
// keyframes (consecutive ones of a robot: odometry refined by matching; loop closures: a keyframe
// matched against older keyframes) and unary prior edges (an operator's initial pose, the first
// keyframe of a segment). Optimised with Ceres; loop-closure edges carry a robust loss so one bad
// closure that slipped through the consistency check cannot drag the graph.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "common/core/geometry.hpp"
#include "common/core/result.hpp"

namespace slam::correction {

using NodeId = uint64_t;

enum class EdgeKind : uint8_t { Sequential, LoopClosure, Prior };

struct GraphEdge {
  EdgeKind kind = EdgeKind::Sequential;
  NodeId from = 0;   // Prior: the node constrained
  NodeId to = 0;     // unused for Prior
  Pose measurement;  // relative: from^-1 ∘ to; Prior: the node's pose in the map
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  // inverse covariance of (x, y, theta)
};

struct OptimiseStats {
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  double max_node_shift_m = 0.0;  // largest position change of any node
  bool converged = false;
};

class PoseGraph {
 public:
  // Adds a node with its initial estimate; ids are unique (an existing id is an error).
  Status add_node(NodeId id, const Pose& estimate, bool fixed = false);
  // Both ends must exist; information must be symmetric positive definite.
  Status add_edge(const GraphEdge& edge);
  Status set_fixed(NodeId id, bool fixed);

  // Runs Ceres over every node and edge, updates the estimates. Loop closures use a Cauchy loss.
  Result<OptimiseStats> optimise(int max_iterations = 50);

  // nullopt for an unknown id.
  std::optional<Pose> estimate(NodeId id) const;
  size_t node_count() const;
  size_t edge_count() const;
  // implementation-defined storage: flat arrays, id -> index map
};

// Whether a candidate loop closure agrees with what the graph already believes: the Mahalanobis
// distance of (predicted^-1 ∘ measured) under `uncertainty` (the covariance accumulated along the
// chain since the two keyframes were last tied together, plus the match's) is below the
// chi-square bound (3 dof). A closure that fails it is rejected: a wrong closure is worse than none.
struct ConsistencyCheck {
  double chi2_bound = 11.34;  // 99 % for 3 dof
  bool accepts(const Pose& predicted_relative, const Pose& measured_relative,
               const Eigen::Matrix3d& uncertainty) const;
};

}  // namespace slam::correction
