#include "pose_correction/graph_optimizer.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>
#include <utility>

#include "square_loop.hpp"

namespace slam::correction {
namespace {

using namespace std::chrono_literals;

PoseGraph closed_square(int keyframes_per_leg = 20) {
  const SquareLoop square = make_square_loop(keyframes_per_leg);
  PoseGraph graph = square.odometry_graph();
  EXPECT_TRUE(graph.add_edge(square.closure()));
  return graph;
}

TEST(GraphOptimizer, DeliversWhatADirectOptimiseGives) {
  PoseGraph direct = closed_square();
  GraphOptimizer optimizer;
  EXPECT_FALSE(optimizer.poll());
  const uint64_t job = optimizer.submit(direct);
  ASSERT_TRUE(direct.optimise());

  ASSERT_TRUE(optimizer.wait_idle(60s));
  ASSERT_TRUE(optimizer.poll());
  const auto result = optimizer.take_result();
  ASSERT_TRUE(result.has_value());
  EXPECT_EQ(result->job, job);
  ASSERT_TRUE(result->status) << result->status.message();
  EXPECT_TRUE(result->stats.converged);
  const std::vector<NodeEstimate> expected = direct.estimates();
  ASSERT_EQ(result->estimates.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(result->estimates[i].id, expected[i].id);
    EXPECT_NEAR(result->estimates[i].pose.x, expected[i].pose.x, 1e-9);
    EXPECT_NEAR(result->estimates[i].pose.y, expected[i].pose.y, 1e-9);
    EXPECT_NEAR(result->estimates[i].pose.theta, expected[i].pose.theta, 1e-9);
  }
  EXPECT_FALSE(optimizer.poll());
  EXPECT_FALSE(optimizer.take_result().has_value());
}

TEST(GraphOptimizer, NewerSubmitsReplaceWaitingOnes) {
  GraphOptimizer optimizer;
  // A long solve first (a quadratic loss makes the badly drifted loop take many steps), so the later submits
  // arrive while it runs (or before it starts: then it is replaced too). The middle one never gets solved
  // either way. The graphs are built beforehand so the submits follow each other within microseconds.
  PoseGraph slow_graph = closed_square(1000), middle_graph = closed_square(), newest_graph = closed_square();
  const uint64_t slow =
      optimizer.submit(std::move(slow_graph), {.max_iterations = 200, .robust_loop_closures = false});
  const uint64_t middle = optimizer.submit(std::move(middle_graph));
  const uint64_t newest = optimizer.submit(std::move(newest_graph));
  EXPECT_LT(slow, middle);
  EXPECT_LT(middle, newest);

  ASSERT_TRUE(optimizer.wait_idle(600s));
  const auto result = optimizer.take_result();
  ASSERT_TRUE(result.has_value());
  EXPECT_EQ(result->job, newest);
  EXPECT_TRUE(result->status) << result->status.message();
  const OptimizerCounters counters = optimizer.counters();
  EXPECT_EQ(counters.submitted, 3u);
  EXPECT_GE(counters.coalesced, 1u);
  EXPECT_EQ(counters.started, counters.solved);
  EXPECT_EQ(counters.coalesced + counters.solved, 3u);
}

TEST(GraphOptimizer, ReportsAFailedSolveAsAResult) {
  GraphOptimizer optimizer;
  const uint64_t job = optimizer.submit(closed_square(), {.max_iterations = 0});
  ASSERT_TRUE(optimizer.wait_idle(60s));
  const auto result = optimizer.take_result();
  ASSERT_TRUE(result.has_value());
  EXPECT_EQ(result->job, job);
  EXPECT_FALSE(result->status);
  EXPECT_TRUE(result->estimates.empty());
  EXPECT_EQ(optimizer.counters().failed, 1u);
}

TEST(GraphOptimizer, ShutsDownDuringALongSolve) {
  auto optimizer = std::make_unique<GraphOptimizer>();
  (void)optimizer->submit(closed_square(1000), {.max_iterations = 1000, .robust_loop_closures = false});
  while (optimizer->counters().started == 0) std::this_thread::yield();
  // The destructor aborts the solve at its next iteration and joins: a hang fails by the test's
  // timeout, a leak or a use after free under the sanitizer build.
  optimizer.reset();
}

}  // namespace
}  // namespace slam::correction
