#pragma once
// A synthetic square drive for the pose-graph tests: four legs of keyframes 0.5 m apart with a
// quarter turn at each corner, odometry that drifts (a steady heading bias plus a little noise) and
// the one loop closure that ties the last keyframe back to the first.
#include <Eigen/Core>
#include <numbers>
#include <random>
#include <vector>

#include "pose_correction/pose_graph.hpp"

namespace slam::correction {

inline Eigen::Matrix3d information(double sigma_m, double sigma_rad) {
  return Eigen::Vector3d{1.0 / (sigma_m * sigma_m), 1.0 / (sigma_m * sigma_m), 1.0 / (sigma_rad * sigma_rad)}
      .asDiagonal();
}

struct SquareLoop {
  std::vector<Pose> truth;          // node i's true pose; the last equals the first
  std::vector<Pose> drifted_start;  // the odometry integrated from the true first pose
  std::vector<GraphEdge> odometry;  // edge i joins node i to node i + 1

  NodeId last() const { return truth.size() - 1; }
  // Nodes at their drifted estimates, the first one fixed, chained by the odometry edges.
  PoseGraph odometry_graph() const {
    PoseGraph graph;
    for (NodeId i = 0; i < drifted_start.size(); ++i) (void)graph.add_node(i, drifted_start[i], i == 0);
    for (const GraphEdge& edge : odometry) (void)graph.add_edge(edge);
    return graph;
  }
  // The last keyframe matched against the first: both are the same place.
  GraphEdge closure() const {
    return {EdgeKind::LoopClosure, last(), 0, truth.back().inverse().compose(truth.front()),
            information(0.01, 0.005)};
  }
};

inline SquareLoop make_square_loop(int keyframes_per_leg = 20, double heading_bias_rad = 0.002) {
  constexpr double kStep = 0.5;
  std::mt19937 rng(42);
  std::normal_distribution<double> linear_noise(0.0, 0.002), angular_noise(0.0, 0.001);
  SquareLoop square;
  square.truth.push_back({});
  square.drifted_start.push_back({});
  const int steps = 4 * keyframes_per_leg;
  for (int k = 0; k < steps; ++k) {
    const double turn = (k + 1) % keyframes_per_leg == 0 ? std::numbers::pi / 2.0 : 0.0;
    const Pose motion{kStep, 0.0, turn};
    const Pose measured{kStep + linear_noise(rng), linear_noise(rng),
                        turn + heading_bias_rad + angular_noise(rng)};
    square.truth.push_back(square.truth.back().compose(motion));
    square.drifted_start.push_back(square.drifted_start.back().compose(measured));
    square.odometry.push_back({EdgeKind::Sequential, static_cast<NodeId>(k), static_cast<NodeId>(k + 1),
                               measured, information(0.01, 0.01)});
  }
  return square;
}

}  // namespace slam::correction
