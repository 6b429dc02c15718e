// GatewayIntake: each kind keeps its order, a drain takes everything, what is pushed while the loop
// works lands in the next drain, the loop wakes for what cannot wait, and a full MQTT queue holds the
// MQTT thread until the loop drains.
#include "gateway/core/gateway_intake.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace slam::gateway {
namespace {

using namespace std::chrono_literals;
using Clock = GatewayIntake::Clock;

InboundMessage message(const std::string& topic, std::size_t hits = 0) {
  InboundMessage m;
  m.topic = topic;
  m.robot_id = topic;
  m.message.kind = protocol::TopicKind::V2Points;
  m.message.observation.hits.assign(hits, protocol::Point{1.0, 2.0});
  return m;
}

void push_message(GatewayIntake& intake, const std::string& topic, std::size_t hits = 0) {
  InboundMessage m = message(topic, hits);
  intake.push(m);
}

std::vector<std::string> topics(const GatewayInputs& in) {
  std::vector<std::string> out;
  for (const InboundMessage& m : in.inbound) out.push_back(m.topic);
  return out;
}

TEST(GatewayIntake, KeepsTheOrderOfEachKind) {
  GatewayIntake intake;
  for (const char* t : {"a", "b", "c"}) push_message(intake, t);
  intake.push(CorrectionInput{"r2", {{1.0, 0.0, 0.0}, 7}});
  intake.push(CorrectionInput{"r1", {{2.0, 0.0, 0.0}, 3}});
  intake.push(WaypointInput{"r1", 2, {1.0, 1.0}, {}});
  intake.push(WaypointInput{"r1", 1, {2.0, 2.0}, {{3.0, 3.0}}});
  intake.push(MqttRequestInput{9, RequestKind::Subscribe, "x/#", {}, 1, false});
  intake.push(MqttRequestInput{4, RequestKind::Publish, "x/y", {1, 2, 3}, 0, true});
  intake.push(PeerHeartbeat{"host:2", false});
  intake.push(PeerHeartbeat{"host:1", true});
  intake.push(ProtocolReport{"r9", {Protocol::V2, 5}});
  intake.push(ProtocolReport{"r8", {Protocol::V1, 6}});
  intake.push_forget("r5");
  intake.push_forget("r4");

  GatewayInputs in;
  intake.drain(in);
  EXPECT_EQ(topics(in), (std::vector<std::string>{"a", "b", "c"}));
  ASSERT_EQ(in.corrections.size(), 2u);
  EXPECT_EQ(in.corrections[0].robot_id, "r2");
  EXPECT_EQ(in.corrections[0].correction.version, 7u);
  EXPECT_EQ(in.corrections[1].robot_id, "r1");
  ASSERT_EQ(in.waypoints.size(), 2u);
  EXPECT_EQ(in.waypoints[0].seq, 2u);
  EXPECT_EQ(in.waypoints[1].seq, 1u);
  ASSERT_EQ(in.waypoints[1].remaining.size(), 1u);
  ASSERT_EQ(in.requests.size(), 2u);
  EXPECT_EQ(in.requests[0].request_id, 9u);
  EXPECT_EQ(in.requests[1].request_id, 4u);
  EXPECT_EQ(in.requests[1].payload, (std::vector<std::uint8_t>{1, 2, 3}));
  ASSERT_EQ(in.heartbeats.size(), 2u);
  EXPECT_EQ(in.heartbeats[0].instance_id, "host:2");
  EXPECT_TRUE(in.heartbeats[1].stopping);
  ASSERT_EQ(in.protocols.size(), 2u);
  EXPECT_EQ(in.protocols[0].robot_id, "r9");
  EXPECT_EQ(in.protocols[1].report.protocol, Protocol::V1);
  EXPECT_EQ(in.forgets, (std::vector<std::string>{"r5", "r4"}));
}

TEST(GatewayIntake, ADrainTakesEverythingAndReplacesWhatItHeld) {
  GatewayIntake intake;
  push_message(intake, "a");
  intake.push(CorrectionInput{"r1", {}});
  intake.push_forget("r1");
  GatewayInputs in;
  intake.drain(in);
  EXPECT_FALSE(in.empty());

  intake.drain(in);
  EXPECT_TRUE(in.empty());

  push_message(intake, "b");
  intake.drain(in);
  EXPECT_EQ(topics(in), (std::vector<std::string>{"b"}));
  EXPECT_TRUE(in.corrections.empty());
  EXPECT_TRUE(in.forgets.empty());
}

TEST(GatewayIntake, PushesWhileTheLoopWorksLandInTheNextDrain) {
  GatewayIntake intake;
  constexpr int kCount = 20000;
  std::atomic<bool> done{false};
  std::thread mqtt([&] {
    for (int i = 0; i < kCount; ++i) push_message(intake, std::to_string(i));
    done.store(true);
  });
  std::thread reader([&] {
    for (int i = 0; i < kCount; ++i) intake.push(CorrectionInput{std::to_string(i), {}});
  });
  std::vector<std::string> messages;
  std::vector<std::string> corrections;
  GatewayInputs in;
  int drains = 0;
  while (messages.size() < static_cast<std::size_t>(kCount) ||
         corrections.size() < static_cast<std::size_t>(kCount)) {
    intake.drain(in);
    ++drains;
    for (const InboundMessage& m : in.inbound) messages.push_back(m.topic);
    for (const CorrectionInput& c : in.corrections) corrections.push_back(c.robot_id);
  }
  mqtt.join();
  reader.join();
  EXPECT_TRUE(done.load());
  intake.drain(in);
  EXPECT_TRUE(in.empty());  // nothing twice, nothing left behind
  ASSERT_EQ(messages.size(), static_cast<std::size_t>(kCount));
  ASSERT_EQ(corrections.size(), static_cast<std::size_t>(kCount));
  for (int i = 0; i < kCount; ++i) {
    ASSERT_EQ(messages[static_cast<std::size_t>(i)], std::to_string(i));
    ASSERT_EQ(corrections[static_cast<std::size_t>(i)], std::to_string(i));
  }
  EXPECT_GT(drains, 1);
}

TEST(GatewayIntake, SpentMessagesComeBackToTheMqttThreadWithTheirBuffers) {
  GatewayIntake intake;
  InboundMessage m = message("a", 100);
  intake.push(m);
  GatewayInputs in;
  intake.drain(in);  // the loop handles "a"
  intake.drain(in);  // and gives it back with the next drain
  InboundMessage next = message("b");
  intake.push(next);
  EXPECT_GE(next.message.observation.hits.capacity(), 100u);
}

TEST(GatewayIntake, WaypointsRequestsAndForgetsWakeTheLoopCorrectionsDoNot) {
  // Pushed while the loop sleeps (a wake is a notification), with a deadline far enough away that
  // only a wake ends the wait early.
  const auto wakes = [](auto push) {
    GatewayIntake intake;
    std::thread pusher([&] {
      std::this_thread::sleep_for(20ms);
      push(intake);
    });
    const auto start = Clock::now();
    intake.wait_until(start + 10s, InboundWake{1000, 1000});
    const auto waited = Clock::now() - start;
    pusher.join();
    return waited < 8s;
  };
  // Queued before a short wait: the wait lasts to its deadline.
  const auto waits_on = [](auto push) {
    GatewayIntake intake;
    push(intake);
    const auto start = Clock::now();
    intake.wait_until(start + 50ms, InboundWake{1000, 1000});
    return Clock::now() - start >= 50ms;
  };
  EXPECT_TRUE(wakes([](GatewayIntake& i) { i.push(WaypointInput{"r", 1, {}, {}}); }));
  EXPECT_TRUE(wakes([](GatewayIntake& i) { i.push(MqttRequestInput{}); }));
  EXPECT_TRUE(wakes([](GatewayIntake& i) { i.push_forget("r"); }));
  EXPECT_TRUE(waits_on([](GatewayIntake& i) { i.push(CorrectionInput{"r", {}}); }));
  EXPECT_TRUE(waits_on([](GatewayIntake& i) { i.push(PeerHeartbeat{"g", false}); }));
  EXPECT_TRUE(waits_on([](GatewayIntake& i) { i.push(ProtocolReport{"r", {}}); }));
  // MQTT messages wake it once there are as many (or as many points) as asked for.
  EXPECT_TRUE(waits_on([](GatewayIntake& i) { push_message(i, "a", 999); }));
  EXPECT_TRUE(wakes([](GatewayIntake& i) {
    push_message(i, "a");
    push_message(i, "b");
    push_message(i, "c", 1000);
  }));
  EXPECT_TRUE(wakes([](GatewayIntake& i) {
    for (int n = 0; n < 1000; ++n) push_message(i, "m");
  }));
}

TEST(GatewayIntake, AWaitReturnsAtOnceForWhatIsQueuedAlreadyOrAtItsDeadline) {
  GatewayIntake intake;
  push_message(intake, "a");
  auto start = Clock::now();
  intake.wait_until(start + 5s);  // one message wakes by default
  EXPECT_LT(Clock::now() - start, 1s);
  start = Clock::now();
  intake.wait_until(start + 30ms, InboundWake{2});
  EXPECT_GE(Clock::now() - start, 30ms);
}

TEST(GatewayIntake, AFullMqttQueueHoldsTheMqttThreadUntilADrain) {
  GatewayIntake intake(2);
  std::atomic<int> pushed{0};
  std::thread mqtt([&] {
    for (const char* t : {"a", "b", "c"}) {
      push_message(intake, t);
      pushed.fetch_add(1);
    }
  });
  // A full queue wakes the loop whatever it waits for.
  intake.wait_until(Clock::now() + 5s, InboundWake{100});
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(pushed.load(), 2);
  GatewayInputs in;
  intake.drain(in);
  mqtt.join();
  EXPECT_EQ(pushed.load(), 3);
  EXPECT_EQ(topics(in), (std::vector<std::string>{"a", "b"}));
  intake.drain(in);
  EXPECT_EQ(topics(in), (std::vector<std::string>{"c"}));
}

TEST(GatewayIntake, CloseLetsAWaitingMqttThreadGoOn) {
  GatewayIntake intake(1);
  push_message(intake, "a");
  std::thread mqtt([&] { push_message(intake, "b"); });
  std::this_thread::sleep_for(20ms);
  intake.close();
  mqtt.join();
  GatewayInputs in;
  intake.drain(in);
  EXPECT_EQ(topics(in), (std::vector<std::string>{"a", "b"}));
}

}  // namespace
}  // namespace slam::gateway
