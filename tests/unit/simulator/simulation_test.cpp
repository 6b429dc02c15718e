// Fleet behaviour: driving to waypoints, never passing walls or other robots, odometry drift,
// beams and reports, spawning rules, pause, random walk, and bit-for-bit determinism per seed.
#include "simulator/core/simulation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "simulator/core/builtin_worlds.hpp"
#include "simulator/core/kinematics.hpp"

namespace slam::sim {
namespace {

using ::testing::HasSubstr;

SimulationConfig exact_config() {
  SimulationConfig c;
  c.sensor.range_noise_sd = 0.0;
  c.sensor.dropout = 0.0;
  c.odometry = {0.0, 0.0};
  return c;
}

Simulation make(World world, SimulationConfig c = exact_config()) {
  auto s = Simulation::create(std::move(world), c);
  EXPECT_TRUE(s) << s.message();
  return std::move(*s);
}

World walled(std::vector<Segment> walls) {
  return std::move(*World::create("walled", {{0, 0}, {10, 10}}, std::move(walls)));
}

// Steps until some robot reports (the first report comes within one report period).
std::span<const RobotReport> next_reports(Simulation& sim) {
  for (int i = 0; i < 100; ++i)
    if (auto reports = sim.step(); !reports.empty()) return reports;
  ADD_FAILURE() << "no report in 100 steps";
  return {};
}

double wall_distance(const World& w, Vec2 p) {
  double best = INFINITY;
  for (const Segment& s : w.walls()) best = std::min(best, std::sqrt(distance_sq(p, s)));
  return best;
}

TEST(Kinematics, TurnsInPlaceBeforeDriving) {
  const RobotConfig rc;
  const Twist behind = drive_command({0, 0, 0}, {-2, 0.1}, 0.05, rc);
  EXPECT_EQ(behind.linear, 0.0);
  EXPECT_DOUBLE_EQ(std::abs(behind.angular), rc.max_angular);
  const Twist ahead = drive_command({0, 0, 0}, {2, 0}, 0.05, rc);
  EXPECT_DOUBLE_EQ(ahead.linear, rc.max_linear);
  EXPECT_DOUBLE_EQ(ahead.angular, 0.0);
  const Twist close = drive_command({0, 0, 0}, {0.01, 0}, 0.05, rc);
  EXPECT_NEAR(close.linear, 0.2, 1e-12);  // slows to stop on the target in one step
}

TEST(Simulation, ReachesWaypoint) {
  Simulation sim = make(*builtin_world("empty"));
  ASSERT_TRUE(sim.spawn({2, 2, 0}, "r1"));
  ASSERT_TRUE(sim.set_waypoint("r1", {6, 7}));
  int steps = 0;
  while (sim.find("r1")->waypoint && steps < 1000) {
    sim.step();
    ++steps;
  }
  const Robot& r = *sim.find("r1");
  EXPECT_FALSE(r.waypoint);
  EXPECT_NEAR(r.true_pose.x, 6.0, 0.05);
  EXPECT_NEAR(r.true_pose.y, 7.0, 0.05);
  // 6.4 m at 0.5 m/s plus the initial turn: about 13-15 s.
  EXPECT_LT(steps * sim.config().dt, 16.0);
}

TEST(Simulation, StopsAtWallNeverPassesIt) {
  Simulation sim = make(walled({{{5, 0}, {5, 10}}}));
  ASSERT_TRUE(sim.spawn({3, 5, 0.3}, "r1"));
  ASSERT_TRUE(sim.set_waypoint("r1", {8, 5.5}));
  const double radius = sim.config().robot.radius;
  for (int i = 0; i < 400; ++i) {
    sim.step();
    const Pose p = sim.find("r1")->true_pose;
    ASSERT_LT(p.x, 5.0);
    ASSERT_GE(wall_distance(sim.world(), {p.x, p.y}), radius - 1e-9);
  }
  // It pressed up against the wall: within a few millimetres of contact.
  EXPECT_NEAR(sim.find("r1")->true_pose.x, 5.0 - radius, 0.01);
}

TEST(Simulation, DiagonalWallIsNotTunnelledThrough) {
  Simulation sim = make(walled({{{2, 8}, {8, 2}}}));
  ASSERT_TRUE(sim.spawn({2, 2, 0.7}, "r1"));
  ASSERT_TRUE(sim.set_waypoint("r1", {8, 8}));
  for (int i = 0; i < 600; ++i) {
    sim.step();
    const Pose p = sim.find("r1")->true_pose;
    ASSERT_LT(p.x + p.y, 10.0 - sim.config().robot.radius * std::sqrt(2.0) + 1e-6);
  }
}

TEST(Simulation, RobotsDoNotOverlap) {
  Simulation sim = make(*builtin_world("empty"));
  ASSERT_TRUE(sim.spawn({2, 5, 0}, "a"));
  ASSERT_TRUE(sim.spawn({8, 5, 3.14159}, "b"));
  ASSERT_TRUE(sim.set_waypoint("a", {9, 5}));
  ASSERT_TRUE(sim.set_waypoint("b", {1, 5}));
  const double r = sim.config().robot.radius;
  for (int i = 0; i < 400; ++i) {
    sim.step();
    const Pose a = sim.find("a")->true_pose, b = sim.find("b")->true_pose;
    ASSERT_GE(std::hypot(a.x - b.x, a.y - b.y), 2.0 * r - 1e-9);
  }
}

TEST(Simulation, HeadOnMeetingCountsOneContactPerPairUntilTheyPart) {
  Simulation sim = make(*builtin_world("empty"));
  ASSERT_TRUE(sim.spawn({2, 5, 0}, "a"));
  ASSERT_TRUE(sim.spawn({8, 5, 3.14159}, "b"));
  ASSERT_TRUE(sim.spawn({2, 2, 0}, "c"));  // drives alone: never touches anyone
  ASSERT_TRUE(sim.set_waypoint("a", {9, 5}));
  ASSERT_TRUE(sim.set_waypoint("b", {1, 5}));
  ASSERT_TRUE(sim.set_waypoint("c", {8, 2}));
  // They stay pressed against each other for many steps: still one contact.
  for (int i = 0; i < 400; ++i) sim.step();
  EXPECT_EQ(sim.contacts(), 1u);
  // Parted and driven together again: a second contact of the same pair.
  ASSERT_TRUE(sim.set_waypoint("a", {1, 5}));
  ASSERT_TRUE(sim.set_waypoint("b", {9, 5}));
  for (int i = 0; i < 100; ++i) sim.step();
  EXPECT_EQ(sim.contacts(), 1u);
  ASSERT_TRUE(sim.set_waypoint("a", {9, 5}));
  ASSERT_TRUE(sim.set_waypoint("b", {1, 5}));
  for (int i = 0; i < 400; ++i) sim.step();
  EXPECT_EQ(sim.contacts(), 2u);
}

TEST(Simulation, RobotsPassingAtADistanceMakeNoContact) {
  Simulation sim = make(*builtin_world("empty"));
  ASSERT_TRUE(sim.spawn({2, 5, 0}, "a"));
  ASSERT_TRUE(sim.spawn({8, 5.4, 3.14159}, "b"));  // lanes 0.4 m apart: 0.1 m between the discs
  ASSERT_TRUE(sim.set_waypoint("a", {8, 5}));
  ASSERT_TRUE(sim.set_waypoint("b", {2, 5.4}));
  for (int i = 0; i < 600; ++i) sim.step();
  EXPECT_EQ(sim.contacts(), 0u);
  EXPECT_FALSE(sim.find("a")->waypoint.has_value());  // both arrived: they did pass each other
  EXPECT_FALSE(sim.find("b")->waypoint.has_value());
}

TEST(Simulation, ZeroNoiseMeansNoDrift) {
  SimulationConfig c = exact_config();
  c.random_walk = true;
  Simulation sim = make(*builtin_world("office"), c);
  ASSERT_TRUE(sim.spawn_random(8));
  for (int i = 0; i < 2000; ++i) sim.step();
  for (const Robot& r : sim.robots()) {
    EXPECT_NEAR(r.reported_pose.x, r.true_pose.x, 1e-9);
    EXPECT_NEAR(r.reported_pose.y, r.true_pose.y, 1e-9);
    EXPECT_NEAR(wrap_angle(r.reported_pose.theta - r.true_pose.theta), 0.0, 1e-9);
  }
}

TEST(Simulation, DriftGrowsWithDistanceDriven) {
  SimulationConfig c;
  c.random_walk = true;
  c.odometry = {0.05, 0.02};
  Simulation sim = make(*builtin_world("office"), c);
  ASSERT_TRUE(sim.spawn_random(32));
  const auto mean_error = [&] {
    double sum = 0.0;
    for (const Robot& r : sim.robots())
      sum += std::hypot(r.reported_pose.x - r.true_pose.x, r.reported_pose.y - r.true_pose.y);
    return sum / static_cast<double>(sim.robots().size());
  };
  std::vector<Pose> last(sim.robots().size());
  double driven = 0.0;
  const auto run = [&](int steps) {
    for (int i = 0; i < steps; ++i) {
      for (size_t k = 0; k < last.size(); ++k) last[k] = sim.robots()[k].true_pose;
      sim.step();
      for (size_t k = 0; k < last.size(); ++k)
        driven +=
            std::hypot(sim.robots()[k].true_pose.x - last[k].x, sim.robots()[k].true_pose.y - last[k].y);
    }
  };
  run(100);  // 5 s
  const double early = mean_error(), early_driven = driven / 32.0;
  run(2300);  // to 120 s
  const double late = mean_error(), late_driven = driven / 32.0;
  EXPECT_GT(early_driven, 0.5);
  EXPECT_GT(late_driven, 10.0 * early_driven);
  EXPECT_GT(early, 0.0);
  EXPECT_GT(late, 2.0 * early) << "early " << early << " m after " << early_driven << " m, late " << late
                               << " m after " << late_driven << " m";
}

TEST(Simulation, ReportsHitWallsExactlyWithoutNoise) {
  Simulation sim = make(*builtin_world("office"));
  ASSERT_TRUE(sim.spawn({12.5, 7.5, 0.2}, "r1"));
  const auto reports = next_reports(sim);
  ASSERT_EQ(reports.size(), 1u);
  const RobotReport& rep = reports[0];
  EXPECT_EQ(rep.robot_id, "r1");
  ASSERT_EQ(rep.ranges.size(), 16u);
  ASSERT_EQ(rep.angles.size(), 16u);
  EXPECT_DOUBLE_EQ(rep.max_range, 4.0);
  size_t hits = 0;
  for (size_t i = 0; i < rep.ranges.size(); ++i) {
    const double world_angle = rep.true_pose.theta + rep.angles[i];
    EXPECT_DOUBLE_EQ(rep.ranges[i],
                     sim.world().cast({12.5, 7.5}, {std::cos(world_angle), std::sin(world_angle)}, 4.0));
    if (rep.ranges[i] < rep.max_range) ++hits;
  }
  ASSERT_EQ(rep.hits.size(), hits);
  EXPECT_GT(hits, 4u);
  for (const Vec2& h : rep.hits) EXPECT_LT(wall_distance(sim.world(), h), 1e-9);
}

TEST(Simulation, StartFrameReportsFromTheOriginAndPlacesHitsInIt) {
  SimulationConfig c = exact_config();
  c.odom_frame = OdomFrame::Start;
  Simulation sim = make(*builtin_world("office"), c);
  const Pose spawn{12.5, 7.5, 0.7};
  ASSERT_TRUE(sim.spawn(spawn, "r1"));
  const auto reports = next_reports(sim);
  ASSERT_EQ(reports.size(), 1u);
  const RobotReport& rep = reports[0];
  EXPECT_EQ(rep.reported_pose.x, 0.0);
  EXPECT_EQ(rep.reported_pose.y, 0.0);
  EXPECT_EQ(rep.reported_pose.theta, 0.0);
  EXPECT_EQ(rep.true_pose.x, spawn.x);
  // Hits are in the start frame: mapped through the spawn pose they lie on the world's walls.
  ASSERT_GT(rep.hits.size(), 4u);
  for (const Vec2& h : rep.hits) EXPECT_LT(wall_distance(sim.world(), spawn.transform(h)), 1e-9);
}

TEST(Simulation, StartFrameWaypointDrivesToTheTruePlace) {
  SimulationConfig c = exact_config();
  c.odom_frame = OdomFrame::Start;
  Simulation sim = make(*builtin_world("empty"), c);
  const Pose spawn{2, 3, std::numbers::pi / 2};
  ASSERT_TRUE(sim.spawn(spawn, "r1"));
  // 4 m ahead and 1 m to the right of where the robot started, which faces +y in the world.
  ASSERT_TRUE(sim.set_waypoint("r1", {4, -1}));
  for (int steps = 0; sim.find("r1")->waypoint && steps < 1000; ++steps) sim.step();
  const Robot& r = *sim.find("r1");
  EXPECT_FALSE(r.waypoint);
  EXPECT_NEAR(r.reported_pose.x, 4.0, 0.05);
  EXPECT_NEAR(r.reported_pose.y, -1.0, 0.05);
  EXPECT_NEAR(r.true_pose.x, 3.0, 0.05);
  EXPECT_NEAR(r.true_pose.y, 7.0, 0.05);
  EXPECT_NEAR(world_from_odom(r).x, spawn.x, 1e-9);
  EXPECT_NEAR(world_from_odom(r).theta, spawn.theta, 1e-9);
}

TEST(Simulation, StartFrameRandomWalkStaysInside) {
  SimulationConfig c = exact_config();
  c.odom_frame = OdomFrame::Start;
  c.random_walk = true;
  c.odometry = {0.05, 0.05};  // targets must follow the drifting frame too
  Simulation sim = make(*builtin_world("office"), c);
  ASSERT_TRUE(sim.spawn_random(10));
  for (int i = 0; i < 1200; ++i) {
    sim.step();
    for (const Robot& r : sim.robots()) ASSERT_TRUE(sim.world().bounds().contains(r.true_pose.position()));
  }
  double driven = 0.0;
  for (const Robot& r : sim.robots()) driven += norm(r.reported_pose.position());
  EXPECT_GT(driven, 5.0);
}

TEST(Simulation, ReportRateFollowsThePeriod) {
  SimulationConfig c = exact_config();
  c.dt = 0.05;
  c.report_period = 0.1;
  Simulation sim = make(*builtin_world("empty"), c);
  ASSERT_TRUE(sim.spawn_random(10));
  size_t total = 0;
  for (int i = 0; i < 200; ++i) total += sim.step().size();  // 10 s
  EXPECT_NEAR(static_cast<double>(total), 10 * 100.0, 10.0);
}

TEST(Simulation, BeamsSeeOtherRobots) {
  SimulationConfig c = exact_config();
  c.sensor.beams = 4;  // 0, 90, 180, 270 degrees
  Simulation sim = make(*builtin_world("empty"), c);
  ASSERT_TRUE(sim.spawn({2, 5, 0}, "a"));
  ASSERT_TRUE(sim.spawn({3, 5, 0}, "b"));
  EXPECT_DOUBLE_EQ(sim.cast({2, 5}, {1, 0}, 4.0, 0), 1.0 - sim.config().robot.radius);
  EXPECT_DOUBLE_EQ(sim.cast({2, 5}, {-1, 0}, 4.0, 0), 2.0);
  ASSERT_TRUE(sim.remove("b"));
  ASSERT_TRUE(sim.spawn({2, 5.6, 0}, "c"));
  bool seen = false;
  for (int i = 0; i < 10 && !seen; ++i)
    for (const RobotReport& rep : sim.step())
      if (rep.robot_id == "a") {
        EXPECT_NEAR(rep.ranges[1], 0.6 - sim.config().robot.radius, 1e-12);  // beam at +90 degrees
        seen = true;
      }
  EXPECT_TRUE(seen);
}

TEST(Simulation, DropoutOneSeesNothing) {
  SimulationConfig c = exact_config();
  c.sensor.dropout = 1.0;
  Simulation sim = make(*builtin_world("office"), c);
  ASSERT_TRUE(sim.spawn({12.5, 7.5, 0}));
  const auto reports = next_reports(sim);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_TRUE(reports[0].hits.empty());
  for (double r : reports[0].ranges) EXPECT_EQ(r, reports[0].max_range);
}

TEST(Simulation, SpawnRules) {
  Simulation sim = make(walled({{{5, 0}, {5, 10}}}));
  EXPECT_THAT(sim.spawn({5.05, 3, 0}).message(), HasSubstr("not free"));
  EXPECT_THAT(sim.spawn({-1, 3, 0}).message(), HasSubstr("not free"));
  EXPECT_THAT(sim.spawn({NAN, 3, 0}).message(), HasSubstr("not finite"));
  const auto first = sim.spawn({2, 2, 0});
  ASSERT_TRUE(first);
  EXPECT_EQ(*first, "sim-1");
  EXPECT_THAT(sim.spawn({2.2, 2, 0}).message(), HasSubstr("another robot"));
  EXPECT_THAT(sim.spawn({3, 3, 0}, "sim-1").message(), HasSubstr("already in use"));
  EXPECT_TRUE(sim.remove("sim-1"));
  EXPECT_FALSE(sim.remove("sim-1"));
  EXPECT_FALSE(sim.set_waypoint("nobody", {1, 1}));
}

TEST(Simulation, RandomSpawnFillsOfficeWithoutOverlap) {
  Simulation sim = make(*builtin_world("office"));
  const auto ids = sim.spawn_random(500);
  ASSERT_TRUE(ids) << ids.message();
  EXPECT_EQ(ids->size(), 500u);
  const double r = sim.config().robot.radius;
  const auto robots = sim.robots();
  for (size_t i = 0; i < robots.size(); ++i) {
    const Vec2 p{robots[i].true_pose.x, robots[i].true_pose.y};
    ASSERT_TRUE(sim.world().is_free(p, r));
    for (size_t j = i + 1; j < robots.size(); ++j)
      ASSERT_GE(std::hypot(p.x - robots[j].true_pose.x, p.y - robots[j].true_pose.y), 2.0 * r);
  }
}

TEST(Simulation, CrowdedWorldRefusesAllOrNothing) {
  Simulation sim = make(*World::create("tiny", {{0, 0}, {1, 1}}, {}));
  const auto ids = sim.spawn_random(50);
  ASSERT_FALSE(ids);
  EXPECT_THAT(ids.message(), HasSubstr("no free pose"));
  EXPECT_TRUE(sim.robots().empty());
}

TEST(Simulation, PauseFreezesEverything) {
  SimulationConfig c = exact_config();
  c.random_walk = true;
  Simulation sim = make(*builtin_world("office"), c);
  ASSERT_TRUE(sim.spawn_random(5));
  for (int i = 0; i < 20; ++i) sim.step();
  const Pose before = sim.robots()[0].true_pose;
  const double t = sim.time();
  sim.pause();
  EXPECT_TRUE(sim.step().empty());
  EXPECT_EQ(sim.time(), t);
  EXPECT_EQ(sim.robots()[0].true_pose.x, before.x);
  sim.resume();
  for (int i = 0; i < 20; ++i) sim.step();
  EXPECT_GT(sim.time(), t);
}

TEST(Simulation, RandomWalkExploresAndStaysInside) {
  SimulationConfig c = exact_config();
  c.random_walk = true;
  Simulation sim = make(*builtin_world("maze"), c);
  ASSERT_TRUE(sim.spawn_random(20));
  std::vector<Pose> start;
  for (const Robot& r : sim.robots()) start.push_back(r.true_pose);
  for (int i = 0; i < 1200; ++i) {
    sim.step();
    for (const Robot& r : sim.robots())
      ASSERT_GE(wall_distance(sim.world(), {r.true_pose.x, r.true_pose.y}), c.robot.radius - 1e-9);
  }
  int moved = 0;
  for (size_t k = 0; k < start.size(); ++k)
    if (std::hypot(sim.robots()[k].true_pose.x - start[k].x, sim.robots()[k].true_pose.y - start[k].y) > 0.5)
      ++moved;
  EXPECT_GE(moved, 15);
}

TEST(Simulation, SameSeedSameRunDifferentSeedDifferentRun) {
  const auto run = [](uint64_t seed) {
    SimulationConfig c;
    c.seed = seed;
    c.random_walk = true;
    c.sensor.dropout = 0.1;
    Simulation sim = make(*builtin_world("office"), c);
    EXPECT_TRUE(sim.spawn_random(20));
    std::vector<double> trace;
    for (int i = 0; i < 300; ++i)
      for (const RobotReport& r : sim.step()) {
        trace.insert(trace.end(), {r.reported_pose.x, r.reported_pose.y, r.true_pose.theta});
        trace.insert(trace.end(), r.ranges.begin(), r.ranges.end());
      }
    return trace;
  };
  const auto a = run(42), b = run(42), c = run(43);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(Simulation, SetWorldRespawnsEveryRobot) {
  Simulation sim = make(*builtin_world("office"));
  ASSERT_TRUE(sim.spawn_random(10));
  ASSERT_TRUE(sim.set_world(*builtin_world("track")));
  EXPECT_EQ(sim.world().name(), "track");
  for (const Robot& r : sim.robots()) EXPECT_TRUE(sim.world().is_free({r.true_pose.x, r.true_pose.y}, 0.15));
}

TEST(Simulation, SetWorldRestartsStartFrameOdometryAtTheOrigin) {
  SimulationConfig c = exact_config();
  c.odom_frame = OdomFrame::Start;
  Simulation sim = make(*builtin_world("office"), c);
  ASSERT_TRUE(sim.spawn_random(3));
  ASSERT_TRUE(sim.set_waypoint(sim.robots()[0].id, {1, 0}));
  for (int i = 0; i < 20; ++i) sim.step();
  EXPECT_GT(norm(sim.robots()[0].reported_pose.position()), 0.1);
  ASSERT_TRUE(sim.set_world(*builtin_world("maze")));
  for (const Robot& r : sim.robots()) {
    EXPECT_EQ(norm(r.reported_pose.position()), 0.0);
    EXPECT_EQ(r.reported_pose.theta, 0.0);
  }
}

TEST(Simulation, StepsForFollowsSpeedFactor) {
  Simulation sim = make(*builtin_world("empty"));
  ASSERT_TRUE(sim.set_speed_factor(2.0));
  EXPECT_EQ(sim.steps_for(0.1), 4u);  // 0.2 s simulated at dt 0.05
  EXPECT_EQ(sim.steps_for(0.01), 0u);
  EXPECT_EQ(sim.steps_for(0.015), 1u);   // the remainder carried over
  EXPECT_EQ(sim.steps_for(100.0), 40u);  // backlog capped at one wall second
  EXPECT_THAT(sim.set_speed_factor(0.0).message(), HasSubstr("speed_factor"));
}

TEST(Config, ValidationNamesTheKey) {
  SimulationConfig c;
  c.sensor.dropout = 1.5;
  EXPECT_THAT(validate(c).message(), HasSubstr("sensor.dropout = 1.5"));
  c = {};
  c.dt = 1.0;
  EXPECT_THAT(validate(c).message(), HasSubstr("more than its radius"));
  c = {};
  c.robot.radius = -1;
  EXPECT_THAT(validate(c).message(), HasSubstr("robot.radius"));
  c = {};
  c.sensor.beams = -3;
  EXPECT_THAT(validate(c).message(), HasSubstr("sensor.beams"));
  c = {};
  c.odometry.drift_per_metre = NAN;
  EXPECT_THAT(validate(c).message(), HasSubstr("odometry.drift_per_metre"));
  EXPECT_TRUE(validate(SimulationConfig{}));
  Simulation sim = make(*builtin_world("empty"));
  EXPECT_THAT(sim.set_noise(0.01, -0.1, 0.0).message(), HasSubstr("sensor.dropout"));
}

}  // namespace
}  // namespace slam::sim
