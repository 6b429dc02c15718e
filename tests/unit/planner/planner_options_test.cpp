// PlannerOptions: defaults are valid, flags land in the core's config, bad values name their key.
#include "planner/core/planner_options.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"

namespace slam::planner {
namespace {

// Parses `args` into fresh options; the CLI11 error text when parsing fails.
std::string parse(PlannerOptions& options, std::vector<std::string> args) {
  CLI::App app{"test"};
  add_planner_options(app, options);
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return {};
}

TEST(PlannerOptions, DefaultsAreValid) {
  PlannerOptions options;
  EXPECT_TRUE(validate(options));
  EXPECT_EQ(options.fleet.planner.unknown, UnknownPolicy::Allowed);
}

TEST(PlannerOptions, FlagsSetTheCoreConfiguration) {
  PlannerOptions o;
  ASSERT_EQ(parse(o, {"--domain",
                      "7",
                      "--goals-reach-tolerance-m",
                      "0.3",
                      "--goals-resend-period-s",
                      "0.5",
                      "--planner-unknown",
                      "blocked",
                      "--planner-ompl-seed",
                      "42",
                      "--planner-ompl-range-m",
                      "2.5",
                      "--planner-goal-algorithm",
                      "fmtstar",
                      "--planner-ompl-fmt-samples",
                      "3000",
                      "--explore-min-cluster-cells",
                      "9",
                      "--request-workers",
                      "3"}),
            "");
  EXPECT_EQ(o.service.domain, 7);
  EXPECT_DOUBLE_EQ(o.fleet.goals.reach_tolerance_m, 0.3);
  EXPECT_DOUBLE_EQ(o.fleet.goals.resend_period_s, 0.5);
  EXPECT_EQ(o.fleet.planner.unknown, UnknownPolicy::Blocked);
  EXPECT_EQ(o.fleet.planner.ompl_seed, 42u);
  EXPECT_DOUBLE_EQ(o.fleet.planner.ompl_range_m, 2.5);
  EXPECT_EQ(o.fleet.planner.goal_algorithm, "fmtstar");
  EXPECT_EQ(o.fleet.planner.ompl_fmt_samples, 3000u);
  EXPECT_EQ(o.fleet.explore.min_cluster_cells, 9u);
  EXPECT_EQ(o.request_workers, 3u);
  EXPECT_TRUE(validate(o));
}

TEST(PlannerOptions, UnknownPolicyAndGoalAlgorithmMustBeNamedOnes) {
  PlannerOptions o;
  EXPECT_NE(parse(o, {"--planner-unknown", "sometimes"}).find("--planner-unknown"), std::string::npos);
  PlannerOptions p;
  EXPECT_NE(parse(p, {"--planner-goal-algorithm", "dijkstra"}).find("--planner-goal-algorithm"),
            std::string::npos);
  EXPECT_EQ(PlannerOptions{}.fleet.planner.goal_algorithm, "astar");
}

TEST(PlannerOptions, TheConfigFileSetsTheUnknownSpacePolicyAndTheGoalAlgorithm) {
  const testkit::TempDir dir("planner-options");
  const auto path = (dir / "planner.yaml").string();
  std::ofstream(path)
      << "planner:\n  unknown: blocked\n  goal_algorithm: fmtstar\n  ompl_fmt_samples: 4000\n";
  PlannerOptions o;
  CLI::App app{"test"};
  add_planner_options(app, o);
  std::vector<std::string> args{"prog", "--config", path};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  EXPECT_FALSE(parse_command_line(app, static_cast<int>(argv.size()), argv.data()));
  EXPECT_EQ(o.fleet.planner.unknown, UnknownPolicy::Blocked);
  EXPECT_EQ(o.fleet.planner.goal_algorithm, "fmtstar");
  EXPECT_EQ(o.fleet.planner.ompl_fmt_samples, 4000u);
}

TEST(PlannerOptions, SharingIsOnUnlessALonePlannerIsAskedFor) {
  PlannerOptions shared;
  ASSERT_EQ(parse(shared, {"--peer-timeout-s", "3"}), "");
  EXPECT_TRUE(shared.share);
  EXPECT_DOUBLE_EQ(shared.peer_timeout_s, 3.0);
  PlannerOptions lone;
  ASSERT_EQ(parse(lone, {"--no-share"}), "");
  EXPECT_FALSE(lone.share);
  EXPECT_TRUE(validate(lone));
}

TEST(PlannerOptions, BadValuesNameTheirKey) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--goals-reach-tolerance-m", "0"}, "reach_tolerance_m"},
      {{"--goals-resend-period-s", "-1"}, "resend_period_s"},
      {{"--planner-unknown-cost-factor", "0.5"}, "unknown_cost_factor"},
      {{"--planner-max-time-budget-s", "0"}, "max_time_budget_s"},
      {{"--planner-goal-time-budget-s", "0"}, "goal_time_budget_s"},
      {{"--planner-ompl-fmt-samples", "10"}, "ompl_fmt_samples"},
      {{"--explore-min-cluster-cells", "0"}, "min_cluster_cells"},
      {{"--explore-return-sigma-m", "-1"}, "explore.return_sigma_m"},
      {{"--explore-tied-sigma-m", "0"}, "explore.tied_sigma_m"},
      {{"--coordination-robot-radius-m", "0"}, "coordination.robot_radius_m"},
      {{"--coordination-clear-stall-s", "0"}, "coordination.clear_stall_s"},
      {{"--loop-rate-hz", "0"}, "loop_rate_hz"},
      {{"--request-workers", "0"}, "request_workers"},
      {{"--request-queue", "0"}, "request_queue"},
      {{"--peer-timeout-s", "0.5"}, "peer_timeout_s"},  // shorter than two heartbeats
  };
  for (const auto& [args, key] : cases) {
    PlannerOptions o;
    ASSERT_EQ(parse(o, args), "") << args.front();
    const Status s = validate(o);
    EXPECT_FALSE(s) << args.front();
    EXPECT_NE(s.message().find(key), std::string::npos) << s.message();
  }
}

}  // namespace
}  // namespace slam::planner
