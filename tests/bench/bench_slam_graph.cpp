// Pose-graph optimisation at fleet size: 10 robots x 1000 keyframes driving laps of one 25 m square
// (each from its own point of the lap), chained by drifting odometry, each robot's first keyframe
// under a prior (its initial pose) and 200 loop closures (half a robot's later lap against its
// first, half against the next robot's keyframes at the same place). Solved from the drifted start.
// With headings: every keyframe also carries the heading its walls gave (the square's sides are
// the walls' axes; 0.5 degrees of noise), as the mapper's graph does when the walls' heading is on.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "pose_correction/pose_graph.hpp"

namespace {

using slam::Pose;
using slam::correction::EdgeKind;
using slam::correction::GraphEdge;
using slam::correction::NodeId;
using slam::correction::PoseGraph;

constexpr int kRobots = 10;
constexpr int kKeyframesPerRobot = 1000;
constexpr int kKeyframesPerLeg = 50;
constexpr int kKeyframesPerLap = 4 * kKeyframesPerLeg;
constexpr int kClosuresPerRobot = 20;
constexpr double kStep = 0.5;

Eigen::Matrix3d information(double sigma_m, double sigma_rad) {
  return Eigen::Vector3d{1.0 / (sigma_m * sigma_m), 1.0 / (sigma_m * sigma_m), 1.0 / (sigma_rad * sigma_rad)}
      .asDiagonal();
}

NodeId node_id(int robot, int keyframe) {
  return static_cast<NodeId>(robot) * kKeyframesPerRobot + static_cast<NodeId>(keyframe);
}

// The pose at a position along the lap (in keyframes from the lap's start corner).
Pose lap_pose(int position) {
  Pose pose;
  for (int k = 0; k < position % kKeyframesPerLap; ++k) {
    pose = pose.compose({kStep, 0.0, (k + 1) % kKeyframesPerLeg == 0 ? std::numbers::pi / 2.0 : 0.0});
  }
  return pose;
}

struct FleetGraph {
  PoseGraph graph;
  std::vector<Pose> truth;  // by node id
};

FleetGraph make_fleet_graph(bool wall_headings) {
  std::mt19937 rng(11);
  std::normal_distribution<double> linear_noise(0.0, 0.005), angular_noise(0.0, 0.001),
      match_noise(0.0, 0.01);
  std::uniform_real_distribution<double> heading_bias(-0.0005, 0.0005);
  std::normal_distribution<double> wall_noise(0.0, 0.5 * std::numbers::pi / 180.0);
  FleetGraph fleet;
  fleet.truth.resize(static_cast<size_t>(kRobots) * kKeyframesPerRobot);
  const auto phase = [](int robot) { return robot * (kKeyframesPerLap / kRobots); };
  for (int robot = 0; robot < kRobots; ++robot) {
    const double bias = heading_bias(rng);
    Pose drifted = lap_pose(phase(robot));
    for (int k = 0; k < kKeyframesPerRobot; ++k) {
      const NodeId id = node_id(robot, k);
      fleet.truth[id] = lap_pose(phase(robot) + k);
      if (k > 0) {
        const Pose motion = fleet.truth[id - 1].inverse().compose(fleet.truth[id]);
        const Pose measured{motion.x + linear_noise(rng), motion.y + linear_noise(rng),
                            motion.theta + bias + angular_noise(rng)};
        drifted = drifted.compose(measured);
        (void)fleet.graph.add_node(id, drifted);
        (void)fleet.graph.add_edge({EdgeKind::Sequential, id - 1, id, measured, information(0.02, 0.01)});
      } else {
        (void)fleet.graph.add_node(id, drifted);
        (void)fleet.graph.add_edge({EdgeKind::Prior, id, 0, drifted, information(0.05, 0.02)});
      }
      if (wall_headings) {
        const double sigma = 0.5 * std::numbers::pi / 180.0;
        (void)fleet.graph.add_edge({EdgeKind::Heading,
                                    id,
                                    0,
                                    {0.0, 0.0, fleet.truth[id].theta + wall_noise(rng)},
                                    information(1.0, sigma)});
      }
    }
  }
  // Closures: a keyframe on a later lap against the same place on the robot's first lap, or against
  // the next robot's keyframe there (its phase is one tenth of a lap ahead).
  const auto closure = [&](NodeId from, NodeId to) {
    const Pose truth = fleet.truth[from].inverse().compose(fleet.truth[to]);
    const Pose measured{truth.x + match_noise(rng), truth.y + match_noise(rng),
                        truth.theta + 0.2 * match_noise(rng)};
    (void)fleet.graph.add_edge({EdgeKind::LoopClosure, from, to, measured, information(0.02, 0.005)});
  };
  for (int robot = 0; robot < kRobots; ++robot) {
    const int next = (robot + 1) % kRobots;
    const int shift = phase(next) - phase(robot);  // next robot's keyframe k - shift is at robot's k
    for (int c = 0; c < kClosuresPerRobot; ++c) {
      const int k = kKeyframesPerLap + c * ((kKeyframesPerRobot - kKeyframesPerLap) / kClosuresPerRobot);
      if (c % 2 == 0) {
        closure(node_id(robot, k), node_id(robot, k % kKeyframesPerLap));
      } else {
        closure(node_id(robot, k),
                node_id(next, ((k - shift) % kKeyframesPerLap + kKeyframesPerLap) % kKeyframesPerLap));
      }
    }
  }
  return fleet;
}

double max_error(const PoseGraph& graph, const std::vector<Pose>& truth) {
  double worst = 0.0;
  for (const auto& node : graph.estimates()) {
    worst = std::max(worst, slam::distance(node.pose.position(), truth[node.id].position()));
  }
  return worst;
}

void BM_OptimiseFleetGraph(benchmark::State& state) {
  const FleetGraph fleet = make_fleet_graph(state.range(0) != 0);
  const slam::correction::OptimiseOptions options;  // what the mapper uses
  slam::correction::OptimiseStats stats;
  PoseGraph solved;
  for (auto _ : state) {
    state.PauseTiming();
    PoseGraph graph = fleet.graph;
    state.ResumeTiming();
    auto result = graph.optimise(options);
    if (!result) {
      state.SkipWithError(result.message().c_str());
      return;
    }
    stats = *result;
    state.PauseTiming();
    solved = std::move(graph);
    state.ResumeTiming();
  }
  state.counters["nodes"] = static_cast<double>(solved.node_count());
  state.counters["edges"] = static_cast<double>(solved.edge_count());
  state.counters["iterations"] = stats.iterations;
  state.counters["converged"] = stats.converged ? 1.0 : 0.0;
  state.counters["start_error_m"] = max_error(fleet.graph, fleet.truth);
  state.counters["max_error_m"] = max_error(solved, fleet.truth);
}
BENCHMARK(BM_OptimiseFleetGraph)
    ->ArgName("wall_headings")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
