// SimTab: every simulator control sends its SimControl with the tab's values and tracks it for
// the simulator's reply; values out of the simulator's ranges show an error and send nothing.
#include "viewer/core/sim_tab.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "fake_command_sink.hpp"

namespace slam::viewer {
namespace {

class SimTabTest : public ::testing::Test {
 protected:
  // Expects exactly one command of `kind`, tracked as the last request named `what`.
  const SimCommand& sent_one(SimCommandKind kind, const std::string& what) {
    EXPECT_TRUE(tab.error.empty()) << tab.error;
    EXPECT_EQ(sink.total(), 1u);
    EXPECT_EQ(sink.sim.size(), 1u);
    if (sink.sim.empty()) sink.sim.emplace_back();
    EXPECT_EQ(sink.sim.back().kind, kind);
    EXPECT_TRUE(state.sim_requests.last());
    if (state.sim_requests.last()) {
      EXPECT_EQ(state.sim_requests.last()->id, sink.last_id);
      EXPECT_EQ(state.sim_requests.last()->what, what);
    }
    return sink.sim.back();
  }
  void expect_refused() {
    EXPECT_EQ(sink.total(), 0u);
    EXPECT_FALSE(tab.error.empty());
    EXPECT_FALSE(state.sim_requests.last());
  }

  ViewerState state{100};
  FakeCommandSink sink;
  SimTab tab;
};

TEST_F(SimTabTest, SpawnSendsTheCount) {
  tab.count = 3;
  tab.spawn(state, sink, 0);
  EXPECT_EQ(sent_one(SimCommandKind::Spawn, "spawn 3 robots").count, 3u);
}

TEST_F(SimTabTest, SpawnCountOutOfRangeIsRefused) {
  for (int count : {0, -2, kMaxSpawn + 1}) {
    tab.count = count;
    tab.spawn(state, sink, 0);
  }
  expect_refused();
}

TEST_F(SimTabTest, RemoveSendsTheRobotId) {
  tab.robot_id = "sim-2";
  tab.remove(state, sink, 0);
  EXPECT_EQ(sent_one(SimCommandKind::Remove, "remove sim-2").robot_id, "sim-2");
}

TEST_F(SimTabTest, RemoveWithoutRobotIdIsRefused) {
  tab.robot_id.clear();
  tab.remove(state, sink, 0);
  expect_refused();
}

TEST_F(SimTabTest, RemoveWithTooLongRobotIdIsRefused) {
  tab.robot_id.assign(kMaxSimRobotId + 1, 'r');
  tab.remove(state, sink, 0);
  expect_refused();
}

TEST_F(SimTabTest, PauseAndResume) {
  tab.pause(state, sink, 0);
  sent_one(SimCommandKind::Pause, "pause");
  sink.sim.clear();
  tab.resume(state, sink, 0);
  sent_one(SimCommandKind::Resume, "resume");
}

TEST_F(SimTabTest, SetWorldSendsTheName) {
  tab.world = "maze";
  tab.set_world(state, sink, 0);
  EXPECT_EQ(sent_one(SimCommandKind::SetWorld, "set world maze").world, "maze");
}

TEST_F(SimTabTest, SetWorldWithoutNameIsRefused) {
  tab.world.clear();
  tab.set_world(state, sink, 0);
  expect_refused();
}

TEST_F(SimTabTest, SetNoiseSendsAllThreeValues) {
  tab.range_noise_sd = 0.02;
  tab.dropout = 0.1;
  tab.odometry_drift = 0.005;
  tab.set_noise(state, sink, 0);
  const SimCommand& c = sent_one(SimCommandKind::SetNoise, "set noise (sd 0.02 m, dropout 0.1, drift 0.005)");
  EXPECT_DOUBLE_EQ(c.range_noise_sd, 0.02);
  EXPECT_DOUBLE_EQ(c.dropout, 0.1);
  EXPECT_DOUBLE_EQ(c.odometry_drift, 0.005);
}

TEST_F(SimTabTest, SetNoiseOutOfRangeIsRefused) {
  tab.range_noise_sd = -0.1;
  tab.set_noise(state, sink, 0);
  tab.range_noise_sd = 0.01;
  tab.dropout = 1.5;
  tab.set_noise(state, sink, 0);
  tab.dropout = 0.0;
  tab.odometry_drift = 11.0;
  tab.set_noise(state, sink, 0);
  tab.odometry_drift = std::nan("");
  tab.set_noise(state, sink, 0);
  expect_refused();
}

TEST_F(SimTabTest, SetSpeedSendsTheFactor) {
  tab.speed_factor = 4.0;
  tab.set_speed(state, sink, 0);
  EXPECT_DOUBLE_EQ(sent_one(SimCommandKind::SetSpeed, "set speed x4").speed_factor, 4.0);
}

TEST_F(SimTabTest, SetSpeedOutOfRangeIsRefused) {
  for (double f : {0.0, -1.0, 1001.0}) {
    tab.speed_factor = f;
    tab.set_speed(state, sink, 0);
  }
  expect_refused();
}

TEST_F(SimTabTest, RefusedSendShowsAnError) {
  sink.refuse = true;
  tab.pause(state, sink, 0);
  EXPECT_NE(tab.error.find("NOT sent"), std::string::npos);
  EXPECT_FALSE(state.sim_requests.last());
}

TEST_F(SimTabTest, SimulatorReplyOrSilenceShowsOnTheTab) {
  tab.robot_id = "ghost";
  tab.remove(state, sink, 0);
  IntakeBatch batch;
  batch.sim_replies.push_back({{sink.last_id, false, "remove: no simulated robot 'ghost'"}});
  state.ingest(batch, 1);
  EXPECT_EQ(state.sim_requests.last()->state, RequestState::Failed);
  EXPECT_EQ(describe(*state.sim_requests.last()),
            "#" + std::to_string(sink.last_id) + " remove ghost: failed: remove: no simulated robot 'ghost'");

  tab.pause(state, sink, 10);
  batch.clear();
  state.ingest(batch, 10 + kReplyTimeoutNs + 1);
  EXPECT_EQ(state.sim_requests.last()->state, RequestState::NoReply);
}

}  // namespace
}  // namespace slam::viewer
