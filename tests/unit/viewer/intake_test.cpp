// The intake between listener threads and the render thread: drain hands over everything once,
// a snapshot drops the patches before it, state topics keep the newest per robot, MQTT is bounded.
#include "viewer/core/intake.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace slam::viewer {
namespace {

TEST(Intake, DrainHandsOverOnce) {
  Intake in;
  in.push(ObservationData{"r", 1, {}, {1.0f, 2.0f}});
  IntakeBatch b;
  in.drain(b);
  EXPECT_EQ(b.observations.size(), 1u);
  in.drain(b);
  EXPECT_TRUE(b.observations.empty());
}

TEST(Intake, SnapshotDropsEarlierPatches) {
  Intake in;
  in.push(msg::GridTiles{1, 5, 0, 1, 0, {0}, {1}});
  in.push(msg::GridSnapshot{1, 6, {}, {}, {}});
  in.push(msg::GridTiles{1, 7, 0, 1, 0, {0}, {1}});
  IntakeBatch b;
  in.drain(b);
  ASSERT_TRUE(b.snapshot);
  ASSERT_EQ(b.patches.size(), 1u);
  EXPECT_EQ(b.patches[0].version, 7u);
}

TEST(Intake, StatesKeepNewestPerRobot) {
  Intake in;
  msg::RobotState a;
  a.robot_id = "a";
  a.messages = 1;
  in.push(msg::RobotState(a));
  a.messages = 2;
  in.push(msg::RobotState(a));
  IntakeBatch b;
  in.drain(b);
  ASSERT_EQ(b.states.size(), 1u);
  EXPECT_EQ(b.states[0].messages, 2u);
}

TEST(Intake, CorrectionsKeepNewestPerRobot) {
  Intake in;
  const auto correction = [](const char* id, uint64_t version) {
    msg::PoseCorrection c;
    c.robot_id = id;
    c.version = version;
    return c;
  };
  in.push(correction("a", 1));
  in.push(correction("a", 2));
  in.push(correction("b", 2));
  IntakeBatch b;
  in.drain(b);
  ASSERT_EQ(b.corrections.size(), 2u);
  EXPECT_EQ(b.corrections[0].version, 2u);
  EXPECT_EQ(b.corrections[1].robot_id, "b");
}

TEST(Intake, MqttBacklogIsBounded) {
  Intake in(4);
  for (uint64_t i = 0; i < 10; ++i) in.push(MqttEntry{i, 0, true, "t", {}, 0});
  IntakeBatch b;
  in.drain(b);
  ASSERT_EQ(b.mqtt.size(), 4u);
  EXPECT_EQ(b.mqtt.front().seq, 6u);
  EXPECT_EQ(b.mqtt_dropped, 6u);
}

TEST(Intake, ConcurrentPushesAreAllDelivered) {
  Intake in;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int i = 0; i < 1000; ++i) in.push(ObservationData{"r", 0, {}, {}});
    });
  size_t got = 0;
  IntakeBatch b;
  for (auto& th : threads) th.join();
  in.drain(b);
  got += b.observations.size();
  EXPECT_EQ(got, 4000u);
}

TEST(IntakeTest, RepliesOfGatewayAndSimulatorArriveApart) {
  Intake in;
  in.push(MqttReplyData{{4, true, "subscribed"}});
  in.push(SimReplyData{{5, false, "unknown robot"}});
  IntakeBatch b;
  in.drain(b);
  ASSERT_EQ(b.mqtt_replies.size(), 1u);
  EXPECT_EQ(b.mqtt_replies[0].request_id, 4u);
  ASSERT_EQ(b.sim_replies.size(), 1u);
  EXPECT_EQ(b.sim_replies[0].message, "unknown robot");
  in.drain(b);
  EXPECT_TRUE(b.mqtt_replies.empty());
  EXPECT_TRUE(b.sim_replies.empty());
}

}  // namespace
}  // namespace slam::viewer
