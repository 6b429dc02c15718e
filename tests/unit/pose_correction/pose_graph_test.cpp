#include "pose_correction/pose_graph.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "square_loop.hpp"

namespace slam::correction {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

double max_error(const PoseGraph& graph, const std::vector<Pose>& truth) {
  double worst = 0.0;
  for (size_t i = 0; i < truth.size(); ++i) {
    worst = std::max(worst, distance(graph.estimate(i)->position(), truth[i].position()));
  }
  return worst;
}

GraphEdge relative(EdgeKind kind, NodeId from, NodeId to, const Pose& measurement, double sigma_m,
                   double sigma_rad) {
  return {kind, from, to, measurement, information(sigma_m, sigma_rad)};
}

TEST(PoseGraph, RejectsDuplicateNodesAndNonFiniteEstimates) {
  PoseGraph graph;
  ASSERT_TRUE(graph.add_node(1, {}));
  EXPECT_FALSE(graph.add_node(1, {1.0, 0.0, 0.0}));
  EXPECT_FALSE(graph.add_node(2, {kNan, 0.0, 0.0}));
  EXPECT_FALSE(graph.add_node(3, {0.0, 0.0, std::numeric_limits<double>::infinity()}));
  EXPECT_EQ(graph.node_count(), 1u);
  EXPECT_EQ(*graph.estimate(1), Pose{});
  EXPECT_FALSE(graph.estimate(2).has_value());
}

TEST(PoseGraph, RejectsEdgesToUnknownNodesOrWithBadValues) {
  PoseGraph graph;
  ASSERT_TRUE(graph.add_node(1, {}));
  ASSERT_TRUE(graph.add_node(2, {1.0, 0.0, 0.0}));
  const Pose step{1.0, 0.0, 0.0};
  EXPECT_FALSE(graph.add_edge(relative(EdgeKind::Sequential, 1, 9, step, 0.1, 0.1)));
  EXPECT_FALSE(graph.add_edge(relative(EdgeKind::Sequential, 9, 1, step, 0.1, 0.1)));
  EXPECT_FALSE(graph.add_edge(relative(EdgeKind::Prior, 9, 0, step, 0.1, 0.1)));
  EXPECT_FALSE(graph.add_edge(relative(EdgeKind::LoopClosure, 1, 1, step, 0.1, 0.1)));
  EXPECT_FALSE(graph.add_edge(relative(EdgeKind::Sequential, 1, 2, {kNan, 0.0, 0.0}, 0.1, 0.1)));

  GraphEdge edge = relative(EdgeKind::Sequential, 1, 2, step, 0.1, 0.1);
  edge.information(2, 2) = -1.0;  // not positive definite
  EXPECT_FALSE(graph.add_edge(edge));
  edge.information = Eigen::Matrix3d::Identity();
  edge.information(0, 1) = 0.5;  // not symmetric
  EXPECT_FALSE(graph.add_edge(edge));
  edge.information = Eigen::Matrix3d::Identity();
  edge.information(1, 1) = kNan;
  EXPECT_FALSE(graph.add_edge(edge));
  edge.information = Eigen::Matrix3d::Zero();  // semi-definite: says nothing
  EXPECT_FALSE(graph.add_edge(edge));

  EXPECT_EQ(graph.edge_count(), 0u);
  EXPECT_TRUE(graph.add_edge(relative(EdgeKind::Sequential, 1, 2, step, 0.1, 0.1)));
  EXPECT_TRUE(graph.add_edge(relative(EdgeKind::Prior, 1, 0, {}, 0.1, 0.1)));
  EXPECT_EQ(graph.edge_count(), 2u);
  EXPECT_FALSE(graph.set_fixed(9, true));
}

TEST(PoseGraph, RejectsNonPositiveIterationLimit) {
  PoseGraph graph;
  ASSERT_TRUE(graph.add_node(1, {}));
  EXPECT_FALSE(graph.optimise({.max_iterations = 0}));
}

TEST(PoseGraph, ClosingTheSquareBringsEveryNodeBackToTruth) {
  const SquareLoop square = make_square_loop();
  PoseGraph open = square.odometry_graph();
  PoseGraph closed = open;
  ASSERT_TRUE(closed.add_edge(square.closure()));

  // Without the closure the odometry is already a perfect fit: nothing moves, the end stays off.
  const auto open_stats = open.optimise();
  ASSERT_TRUE(open_stats) << open_stats.message();
  EXPECT_GT(distance(open.estimate(square.last())->position(), square.truth.back().position()), 0.5);

  const auto stats = closed.optimise();
  ASSERT_TRUE(stats) << stats.message();
  EXPECT_TRUE(stats->converged);
  EXPECT_LT(stats->final_cost, stats->initial_cost);
  EXPECT_GT(stats->max_node_shift_m, 0.5);
  EXPECT_LT(max_error(closed, square.truth), 0.05);
  for (const NodeEstimate& node : closed.estimates()) {
    EXPECT_LE(std::abs(node.pose.theta), std::numbers::pi) << "node " << node.id;
    EXPECT_NEAR(wrap_angle(node.pose.theta - square.truth[node.id].theta), 0.0, 0.02) << "node " << node.id;
  }
}

TEST(PoseGraph, FixedNodesStayWhereTheyAre) {
  const SquareLoop square = make_square_loop();
  PoseGraph graph = square.odometry_graph();
  ASSERT_TRUE(graph.add_edge(square.closure()));
  // Pin a node mid-loop at its drifted estimate as well: it must not move although the closure pulls.
  const Pose pinned = *graph.estimate(40);
  ASSERT_TRUE(graph.set_fixed(40, true));
  ASSERT_TRUE(graph.optimise());
  EXPECT_EQ(*graph.estimate(0), square.truth.front());
  EXPECT_EQ(*graph.estimate(40), pinned);
  // Between the two fixed nodes the odometry already fits; beyond the second the closure bends the chain.
  EXPECT_LT(distance(graph.estimate(20)->position(), square.drifted_start[20].position()), 1e-6);
  EXPECT_GT(distance(graph.estimate(60)->position(), square.drifted_start[60].position()), 0.1);
}

TEST(PoseGraph, PriorPullsAFreeGraph) {
  PoseGraph graph;
  ASSERT_TRUE(graph.add_node(1, {}));
  ASSERT_TRUE(graph.add_node(2, {1.0, 0.0, 0.0}));
  ASSERT_TRUE(graph.add_edge(relative(EdgeKind::Sequential, 1, 2, {1.0, 0.0, 0.0}, 0.01, 0.01)));
  const Pose prior{5.0, -2.0, 3.0};  // heading near pi: the angle residual must wrap
  ASSERT_TRUE(graph.add_edge(relative(EdgeKind::Prior, 1, 0, prior, 0.01, 0.01)));
  ASSERT_TRUE(graph.optimise());
  const Pose first = *graph.estimate(1), second = *graph.estimate(2);
  EXPECT_NEAR(first.x, prior.x, 1e-6);
  EXPECT_NEAR(first.y, prior.y, 1e-6);
  EXPECT_NEAR(wrap_angle(first.theta - prior.theta), 0.0, 1e-6);
  const Pose expected = prior.compose({1.0, 0.0, 0.0});
  EXPECT_NEAR(second.x, expected.x, 1e-6);
  EXPECT_NEAR(second.y, expected.y, 1e-6);
}

TEST(PoseGraph, HeadingEdgesTurnAChainAndLeaveItsLengthAlone) {
  // Three nodes a metre apart whose odometry turned 2 degrees at each step; the walls say every
  // heading is 0. The first node is fixed: the chain straightens about it.
  PoseGraph graph;
  const double turn = 2.0 * std::numbers::pi / 180.0;
  ASSERT_TRUE(graph.add_node(0, {}, true));
  Pose drifted;
  for (NodeId id = 1; id <= 2; ++id) {
    drifted = drifted.compose({1.0, 0.0, turn});
    ASSERT_TRUE(graph.add_node(id, drifted));
    ASSERT_TRUE(graph.add_edge(relative(EdgeKind::Sequential, id - 1, id, {1.0, 0.0, turn}, 0.01, 0.05)));
  }
  for (NodeId id = 1; id <= 2; ++id) {
    GraphEdge heading{EdgeKind::Heading, id, 0, {0.0, 0.0, 0.0}, Eigen::Matrix3d::Zero()};
    heading.information(2, 2) = 1.0 / (0.002 * 0.002);
    ASSERT_TRUE(graph.add_edge(heading));
  }
  ASSERT_TRUE(graph.optimise());
  EXPECT_NEAR(graph.estimate(1)->theta, 0.0, 0.002);
  EXPECT_NEAR(graph.estimate(2)->theta, 0.0, 0.002);
  EXPECT_NEAR(graph.estimate(2)->y, 0.0, 0.01);
  EXPECT_NEAR(graph.estimate(2)->x, 2.0, 0.01);

  GraphEdge bad{EdgeKind::Heading, 1, 0, {0.0, 0.0, kNan}, Eigen::Matrix3d::Identity()};
  EXPECT_FALSE(graph.add_edge(bad));  // non-finite heading
  bad.measurement.theta = 0.0;
  bad.information(2, 2) = 0.0;
  EXPECT_FALSE(graph.add_edge(bad));  // no information
  bad.information(2, 2) = 1.0;
  bad.from = 9;
  EXPECT_FALSE(graph.add_edge(bad));  // unknown node
}

TEST(PoseGraph, UnanchoredGraphHoldsItsFirstNode) {
  PoseGraph graph;
  ASSERT_TRUE(graph.add_node(7, {2.0, 3.0, 0.5}));
  ASSERT_TRUE(graph.add_node(8, {0.0, 0.0, 0.0}));
  ASSERT_TRUE(graph.add_edge(relative(EdgeKind::Sequential, 7, 8, {1.0, 0.0, 0.0}, 0.01, 0.01)));
  ASSERT_TRUE(graph.optimise());
  EXPECT_EQ(*graph.estimate(7), (Pose{2.0, 3.0, 0.5}));
  const Pose expected = Pose{2.0, 3.0, 0.5}.compose({1.0, 0.0, 0.0});
  EXPECT_NEAR(graph.estimate(8)->x, expected.x, 1e-6);
  EXPECT_NEAR(graph.estimate(8)->y, expected.y, 1e-6);
}

TEST(PoseGraph, CancelledSolveLeavesTheEstimatesUntouched) {
  const SquareLoop square = make_square_loop();
  PoseGraph graph = square.odometry_graph();
  ASSERT_TRUE(graph.add_edge(square.closure()));
  const std::atomic<bool> cancel{true};
  const auto stats = graph.optimise({.cancel = &cancel});
  ASSERT_FALSE(stats);
  EXPECT_EQ(graph.estimates(), square.odometry_graph().estimates());
}

TEST(PoseGraph, RobustLossLimitsTheDamageOfAWrongClosure) {
  const SquareLoop square = make_square_loop();
  PoseGraph graph = square.odometry_graph();
  ASSERT_TRUE(graph.add_edge(square.closure()));
  ASSERT_TRUE(graph.optimise());
  // A confident match between opposite corners that is 1 m off.
  const Pose wrong = square.truth[20].inverse().compose(square.truth[60]).compose({1.0, 0.0, 0.0});
  ASSERT_TRUE(graph.add_edge(relative(EdgeKind::LoopClosure, 20, 60, wrong, 0.02, 0.01)));

  PoseGraph quadratic = graph;
  ASSERT_TRUE(graph.optimise());
  ASSERT_TRUE(quadratic.optimise({.robust_loop_closures = false}));
  const double robust_error = max_error(graph, square.truth),
               quadratic_error = max_error(quadratic, square.truth);
  EXPECT_LT(robust_error, 0.1);
  EXPECT_GT(quadratic_error, 0.3);
  EXPECT_LT(4.0 * robust_error, quadratic_error);
}

TEST(ConsistencyCheck, AcceptsTheTrueClosureAndRejectsOneAMetreOff) {
  const SquareLoop square = make_square_loop();
  PoseGraph graph = square.odometry_graph();
  ASSERT_TRUE(graph.add_edge(square.closure()));
  ASSERT_TRUE(graph.optimise());
  const Pose predicted = graph.estimate(20)->inverse().compose(*graph.estimate(60));
  const Pose truth = square.truth[20].inverse().compose(square.truth[60]);
  const Pose wrong = truth.compose({1.0, 0.0, 0.0});

  // The chain 20 -> 60 of odometry edges plus the match's own covariance.
  const auto chain = accumulate_chain(std::span(square.odometry).subspan(20, 40));
  ASSERT_TRUE(chain) << chain.message();
  const Eigen::Matrix3d uncertainty = chain->covariance + information(0.02, 0.01).inverse();
  const ConsistencyCheck check;
  EXPECT_TRUE(check.accepts(predicted, truth, uncertainty));
  EXPECT_FALSE(check.accepts(predicted, wrong, uncertainty));
}

TEST(ConsistencyCheck, WrapsTheHeadingDifference) {
  const ConsistencyCheck check;
  const Eigen::Matrix3d uncertainty = Eigen::Vector3d{0.01, 0.01, 0.001}.asDiagonal();
  EXPECT_TRUE(
      check.accepts({1.0, 0.0, std::numbers::pi - 0.01}, {1.0, 0.0, -std::numbers::pi + 0.01}, uncertainty));
  EXPECT_FALSE(check.accepts({1.0, 0.0, 0.0}, {1.0, 0.0, 0.5}, uncertainty));
}

TEST(ConsistencyCheck, RejectsUnderABrokenUncertainty) {
  const ConsistencyCheck check;
  EXPECT_FALSE(check.accepts({}, {}, Eigen::Matrix3d::Zero()));
  EXPECT_FALSE(check.accepts({}, {}, -Eigen::Matrix3d::Identity()));
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(0, 0) = kNan;
  EXPECT_FALSE(check.accepts({}, {}, nan));
  EXPECT_FALSE(check.accepts({kNan, 0.0, 0.0}, {}, Eigen::Matrix3d::Identity()));
  EXPECT_TRUE(check.accepts({}, {}, Eigen::Matrix3d::Identity()));
}

TEST(ComposeCovariance, MatchesAMonteCarloEstimate) {
  const Pose a{1.0, 2.0, 0.7}, b{3.0, -1.0, 0.4};
  Eigen::Matrix3d ca, cb;
  ca << 0.04, 0.01, 0.002, 0.01, 0.02, -0.001, 0.002, -0.001, 0.0009;
  cb << 0.01, -0.004, 0.0, -0.004, 0.03, 0.001, 0.0, 0.001, 0.0016;
  const Eigen::Matrix3d la = ca.llt().matrixL(), lb = cb.llt().matrixL();

  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  const auto sample = [&](const Pose& mean, const Eigen::Matrix3d& l) {
    const Eigen::Vector3d d = l * Eigen::Vector3d{normal(rng), normal(rng), normal(rng)};
    return Pose{mean.x + d.x(), mean.y + d.y(), mean.theta + d.z()};
  };
  const Pose mean = a.compose(b);
  constexpr int kSamples = 200'000;
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (int i = 0; i < kSamples; ++i) {
    const Pose c = sample(a, la).compose(sample(b, lb));
    const Eigen::Vector3d d{c.x - mean.x, c.y - mean.y, wrap_angle(c.theta - mean.theta)};
    sum += d * d.transpose();
  }
  const Eigen::Matrix3d monte_carlo = sum / kSamples;
  const Eigen::Matrix3d first_order = compose_covariance(a, ca, b, cb);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const double scale = std::sqrt(monte_carlo(r, r) * monte_carlo(c, c));
      EXPECT_NEAR(first_order(r, c), monte_carlo(r, c), 0.03 * scale) << "entry " << r << "," << c;
    }
  }
  // The rotation of a carries b's translation uncertainty: not simply ca + cb.
  EXPECT_GT((first_order - (ca + cb)).cwiseAbs().maxCoeff(), 0.01);
}

TEST(AccumulateChain, ComposesStepByStep) {
  const Pose step{0.5, 0.1, 0.2};
  const Eigen::Matrix3d info = information(0.05, 0.02);
  std::vector<GraphEdge> chain;
  for (NodeId i = 0; i < 3; ++i) chain.push_back({EdgeKind::Sequential, i, i + 1, step, info});
  const auto total = accumulate_chain(chain);
  ASSERT_TRUE(total) << total.message();
  const Eigen::Matrix3d c = info.inverse();
  const Eigen::Matrix3d two = compose_covariance(step, c, step, c);
  const Eigen::Matrix3d three = compose_covariance(step.compose(step), two, step, c);
  EXPECT_TRUE(total->covariance.isApprox(three, 1e-12));
  const Pose expected = step.compose(step).compose(step);
  EXPECT_NEAR(total->pose.x, expected.x, 1e-12);
  EXPECT_NEAR(total->pose.y, expected.y, 1e-12);
  EXPECT_NEAR(total->pose.theta, expected.theta, 1e-12);

  const auto empty = accumulate_chain({});
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->pose, Pose{});
  EXPECT_TRUE(empty->covariance.isZero());
}

TEST(AccumulateChain, RejectsBrokenChainsAndPriors) {
  const Eigen::Matrix3d info = Eigen::Matrix3d::Identity();
  const std::vector<GraphEdge> gap{{EdgeKind::Sequential, 0, 1, {}, info},
                                   {EdgeKind::Sequential, 2, 3, {}, info}};
  EXPECT_FALSE(accumulate_chain(gap));
  const std::vector<GraphEdge> prior{{EdgeKind::Prior, 0, 0, {}, info}};
  EXPECT_FALSE(accumulate_chain(prior));
}

}  // namespace
}  // namespace slam::correction
