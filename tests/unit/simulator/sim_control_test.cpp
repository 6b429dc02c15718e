// Operator commands: each kind applied, and every impossible value refused without changing the fleet.
#include "simulator/core/sim_control.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "simulator/core/builtin_worlds.hpp"

namespace slam::sim {
namespace {

using ::testing::HasSubstr;

Simulation make_sim() {
  auto s = Simulation::create(std::move(*builtin_world("empty")), SimulationConfig{});
  EXPECT_TRUE(s) << s.message();
  return std::move(*s);
}

ControlCommand command(ControlKind kind) {
  ControlCommand c;
  c.kind = kind;
  return c;
}

TEST(ApplyControl, SpawnsAtRandomAndAtGivenPoses) {
  Simulation sim = make_sim();
  ControlCommand c = command(ControlKind::Spawn);
  c.count = 3;
  auto out = apply_control(sim, c);
  ASSERT_TRUE(out) << out.message();
  EXPECT_EQ(out->spawned.size(), 3u);
  EXPECT_EQ(sim.robots().size(), 3u);

  c.count = 0;
  c.poses = {{1.0, 1.0, 0.0}};
  c.robot_id = "named";
  out = apply_control(sim, c);
  ASSERT_TRUE(out) << out.message();
  ASSERT_EQ(out->spawned.size(), 1u);
  EXPECT_EQ(out->spawned[0], "named");
  EXPECT_DOUBLE_EQ(sim.find("named")->true_pose.x, 1.0);
}

TEST(ApplyControl, SpawnRefusalsChangeNothing) {
  Simulation sim = make_sim();
  ControlCommand c = command(ControlKind::Spawn);
  EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("count is 0"));
  c.count = static_cast<uint32_t>(kMaxFleet + 1);
  EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("limit"));
  c.count = 3;
  c.poses = {{1.0, 1.0, 0.0}, {2.0, 2.0, 0.0}};
  EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("does not match"));
  c.count = 0;
  c.robot_id = "two poses";
  EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("exactly one pose"));
  c.poses = {{1.0, 1.0, 0.0}};
  c.robot_id = "bad/id";
  EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("'/'"));
  // All or none: the second pose is inside a border wall, so the first robot is taken out again.
  c.robot_id.clear();
  c.poses = {{1.0, 1.0, 0.0}, {0.0, 5.0, 0.0}};
  EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("not free"));
  c.poses = {{std::numeric_limits<double>::quiet_NaN(), 1.0, 0.0}};
  EXPECT_FALSE(apply_control(sim, c));
  EXPECT_TRUE(sim.robots().empty());
}

TEST(ApplyControl, RemovePauseResume) {
  Simulation sim = make_sim();
  ASSERT_TRUE(sim.spawn({5.0, 5.0, 0.0}, "r1"));
  ControlCommand c = command(ControlKind::Remove);
  c.robot_id = "nobody";
  EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("no simulated robot 'nobody'"));
  c.robot_id = "r1";
  auto out = apply_control(sim, c);
  ASSERT_TRUE(out);
  EXPECT_EQ(out->removed, std::vector<std::string>{"r1"});
  EXPECT_TRUE(sim.robots().empty());
  ASSERT_TRUE(apply_control(sim, command(ControlKind::Pause)));
  EXPECT_TRUE(sim.paused());
  ASSERT_TRUE(apply_control(sim, command(ControlKind::Resume)));
  EXPECT_FALSE(sim.paused());
}

TEST(ApplyControl, SetWorldMovesTheFleet) {
  Simulation sim = make_sim();
  ASSERT_TRUE(sim.spawn_random(2));
  ControlCommand c = command(ControlKind::SetWorld);
  auto out = apply_control(sim, c);
  EXPECT_THAT(out.message(), HasSubstr("no world given"));
  c.world = "no-such-world";
  EXPECT_FALSE(apply_control(sim, c));
  EXPECT_EQ(sim.world().name(), "empty");
  c.world = "maze";
  out = apply_control(sim, c);
  ASSERT_TRUE(out) << out.message();
  EXPECT_TRUE(out->world_changed);
  EXPECT_EQ(sim.world().name(), "maze");
  for (const Robot& r : sim.robots()) EXPECT_TRUE(sim.world().is_free({r.true_pose.x, r.true_pose.y}, 0.1));
}

TEST(ApplyControl, NoiseAndSpeedAreRangeChecked) {
  Simulation sim = make_sim();
  ControlCommand c = command(ControlKind::SetNoise);
  c.range_noise_sd = 0.05;
  c.dropout = 0.1;
  c.odometry_drift = 0.03;
  ASSERT_TRUE(apply_control(sim, c));
  EXPECT_DOUBLE_EQ(sim.config().sensor.range_noise_sd, 0.05);
  c.dropout = 1.5;
  EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("sensor.dropout"));
  c.dropout = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(apply_control(sim, c));
  EXPECT_DOUBLE_EQ(sim.config().sensor.dropout, 0.1);

  c = command(ControlKind::SetSpeed);
  c.speed_factor = 4.0;
  ASSERT_TRUE(apply_control(sim, c));
  EXPECT_DOUBLE_EQ(sim.config().speed_factor, 4.0);
  for (double bad : {0.0, -1.0, 1e9, std::numeric_limits<double>::infinity()}) {
    c.speed_factor = bad;
    EXPECT_THAT(apply_control(sim, c).message(), HasSubstr("speed_factor")) << bad;
  }
  EXPECT_DOUBLE_EQ(sim.config().speed_factor, 4.0);
}

}  // namespace
}  // namespace slam::sim
