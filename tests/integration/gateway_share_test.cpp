// Two slam-gateways sharing the robots behind one mosquitto: each robot message reaches DDS exactly
// once (MQTT shared subscriptions), each waypoint command reaches its robot exactly once (one owner
// gateway per robot), both gateways carry a share, and after `kill -9` of one the other takes its
// robots; a viewer's MQTT request is executed by one gateway only. Takeover time and the robot messages lost
// in the kill are measured and printed, not asserted (docs/services.md, the gateway section, holds the
// figures).
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "common/fastdds/requester.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"
#include "robot_publishers.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::bin_path;
using testkit::wait_until;
using Clock = std::chrono::steady_clock;

constexpr int kRobots = 24;

std::string robot_id(int i) {
  return "share-" + std::to_string(i);
}

// One message from every robot carrying `marker`.
void publish_round(testkit::RobotPublishers& publishers, int64_t marker) {
  char line[96];
  std::snprintf(line, sizeof line, "{\"x\": %.2f, \"y\": 0.0, \"heading\": 0.0}",
                static_cast<double>(marker) / 100.0);
  publishers.publish_all(line);
}

// A robot message is told apart by its pose: x = marker / 100 (exact enough to round back).
int64_t marker_of(const RobotObservation& o) {
  return std::llround(o.pose().x() * 100.0);
}

class GatewayShareTest : public ::testing::Test {
 protected:
  void SetUp() override {
    port = group.start_mosquitto();
    participant = std::move(*dds::Participant::create(domain.id(), "gateway-share-test"));
    observation_reader = testkit::make_observation_reader(*participant, [this](const RobotObservation& o) {
      std::lock_guard lock(mutex);
      ++observations[{std::string(o.robot_id().c_str()), marker_of(o)}];
    });
    heartbeat_reader =
        std::move(*dds::make_reader(*participant, dds::kHeartbeat, [this](const Heartbeat& h, const auto&) {
          if (h.service() != std::string("gateway")) return;
          std::lock_guard lock(mutex);
          auto& counters = gateway_counters[std::string(h.instance_id().c_str())];
          for (const auto& c : h.counters()) counters[std::string(c.name().c_str())] = c.value();
        }));
    waypoint_writer = testkit::make_test_writer(*participant, dds::kWaypointCommand);
    for (const char* name : {"gw-a", "gw-b"}) {
      group.start(name, {bin_path("slam-gateway"), "--domain", std::to_string(domain.id()), "--broker",
                         "tcp://127.0.0.1:" + std::to_string(port), "--log-level", "debug"});
    }
    std::vector<std::string> topics;
    for (int i = 0; i < kRobots; ++i) topics.push_back("v2/robot/" + robot_id(i) + "/pose");
    publishers = std::make_unique<testkit::RobotPublishers>(port, topics, "share-pub");
    ASSERT_TRUE(publishers->ok());
    robots = std::make_unique<testkit::MqttTestClient>(port, "share-robots");
    ASSERT_EQ(robots->connect(), 0);
    ASSERT_TRUE(robots->subscribe("v2/server/+/waypoint"));
  }

  // Counter `name` of every gateway heard, by instance id.
  std::map<std::string, int64_t> counter(const std::string& name) {
    std::lock_guard lock(mutex);
    std::map<std::string, int64_t> out;
    for (const auto& [instance, counters] : gateway_counters) {
      const auto it = counters.find(name);
      out[instance] = it == counters.end() ? -1 : it->second;
    }
    return out;
  }
  // True when `n` gateways report `name` >= `at_least`.
  bool all_report(const std::string& name, int64_t at_least, size_t n = 2) {
    size_t ok = 0;
    for (const auto& [instance, value] : counter(name)) ok += value >= at_least ? 1 : 0;
    return ok >= n;
  }

  void send_waypoints(uint64_t seq) {
    for (int i = 0; i < kRobots; ++i) {
      WaypointCommand c;
      c.robot_id(robot_id(i));
      c.seq(seq);
      c.waypoint().x(1.0);
      c.waypoint().y(2.0);
      ASSERT_TRUE(waypoint_writer->write(c));
    }
  }

  // Waypoints the robots received: (robot, seq) -> copies, and when each robot last got one.
  std::map<std::pair<std::string, uint64_t>, int> waypoints_received() {
    std::map<std::pair<std::string, uint64_t>, int> out;
    for (const auto& m : robots->messages()) {
      const std::string robot = m.topic.substr(10, m.topic.size() - 10 - 9);  // v2/server/<id>/waypoint
      ++out[{robot, nlohmann::json::parse(m.payload)["seq"].get<uint64_t>()}];
    }
    return out;
  }

  size_t observation_count(const std::string& robot, int64_t marker) {
    std::lock_guard lock(mutex);
    const auto it = observations.find({robot, marker});
    return it == observations.end() ? 0 : static_cast<size_t>(it->second);
  }

  testkit::DomainLease domain;
  testkit::ProcessGroup group;
  int port = 0;
  std::mutex mutex;
  std::map<std::pair<std::string, int64_t>, int> observations;
  std::map<std::string, std::map<std::string, int64_t>> gateway_counters;
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Reader<RobotObservationBatch>> observation_reader;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader;
  std::unique_ptr<dds::Writer<WaypointCommand>> waypoint_writer;
  std::unique_ptr<testkit::RobotPublishers> publishers;
  std::unique_ptr<testkit::MqttTestClient> robots;  // receives the waypoints
};

TEST_F(GatewayShareTest, EachMessageAndWaypointOnceAndTheSurvivorTakesOverAfterAKill) {
  // Both gateways up, each hearing the other, connected to the broker.
  ASSERT_TRUE(wait_until([&] { return all_report("gateways_live", 2); }, 20s))
      << group.log("gw-a") << group.log("gw-b");

  // Robot messages: every one reaches DDS exactly once, and both gateways receive a share.
  int64_t marker = 0;
  for (int round = 0; round < 20; ++round) publish_round(*publishers, ++marker);
  const int64_t steady_markers = marker;
  ASSERT_TRUE(wait_until(
      [&] {
        for (int i = 0; i < kRobots; ++i)
          for (int64_t m = 1; m <= steady_markers; ++m)
            if (observation_count(robot_id(i), m) == 0) return false;
        return true;
      },
      20s))
      << "robot messages missing on DDS\n"
      << group.log("gw-a") << group.log("gw-b");
  std::this_thread::sleep_for(500ms);  // a duplicate would show up by now
  for (int i = 0; i < kRobots; ++i)
    for (int64_t m = 1; m <= steady_markers; ++m)
      EXPECT_EQ(observation_count(robot_id(i), m), 1u) << robot_id(i) << " message " << m;
  for (const auto& [instance, received] : counter("messages_in")) EXPECT_GT(received, 0) << instance;

  // Waypoints: once both are past their warm-up and know every robot (robots_owned counts robots
  // from the RobotStates), each command reaches its robot exactly once.
  ASSERT_TRUE(wait_until(
      [&] {
        int64_t owned = 0;
        for (const auto& [instance, n] : counter("robots_owned")) owned += std::max<int64_t>(n, 0);
        return owned == kRobots;
      },
      20s))
      << group.log("gw-a") << group.log("gw-b");
  const auto owned = counter("robots_owned");
  for (const auto& [instance, n] : owned) EXPECT_GT(n, 0) << instance << " owns no robot";
  uint64_t seq = 0;
  for (int round = 0; round < 5; ++round) {
    ASSERT_NO_FATAL_FAILURE(send_waypoints(++seq));
    std::this_thread::sleep_for(200ms);
  }
  const uint64_t steady_seqs = seq;
  ASSERT_TRUE(wait_until([&] { return waypoints_received().size() == kRobots * steady_seqs; }, 10s))
      << "waypoints missing: " << waypoints_received().size() << " of " << kRobots * steady_seqs;
  for (const auto& [instance, sent] : counter("commands_sent")) EXPECT_GT(sent, 0) << instance;

  // kill -9 one gateway under load: robots keep publishing, commands keep coming every 200 ms.
  std::atomic<bool> publishing{true};
  std::atomic<int64_t> last_marker{marker};
  std::thread load([&] {
    int64_t m = last_marker.load();
    while (publishing) {  // kRobots x 50 Hz
      publish_round(*publishers, ++m);
      last_marker = m;
      std::this_thread::sleep_for(20ms);
    }
  });
  std::this_thread::sleep_for(500ms);
  const int64_t first_load_marker = marker + 1;
  group.stop("gw-a", SIGKILL);
  const auto killed_at = Clock::now();
  // Takeover: every robot has received a waypoint sent after the kill.
  const uint64_t first_after_kill = seq + 1;
  std::set<std::string> served;
  std::map<std::string, double> served_after_s;
  while (served.size() < kRobots && Clock::now() - killed_at < 20s) {
    ASSERT_NO_FATAL_FAILURE(send_waypoints(++seq));
    std::this_thread::sleep_for(200ms);
    for (const auto& m : robots->messages()) {
      if (m.received_at < killed_at) continue;
      const std::string robot = m.topic.substr(10, m.topic.size() - 10 - 9);
      if (nlohmann::json::parse(m.payload)["seq"].get<uint64_t>() < first_after_kill) continue;
      if (served.insert(robot).second) {
        served_after_s[robot] = std::chrono::duration<double>(m.received_at - killed_at).count();
      }
    }
  }
  publishing = false;
  load.join();
  publishers->close();  // waits until every queued message has gone out
  ASSERT_EQ(served.size(), static_cast<size_t>(kRobots)) << "robots without waypoints after the kill\n"
                                                         << group.log("gw-b");
  double takeover_s = 0.0;
  for (const auto& [robot, s] : served_after_s) takeover_s = std::max(takeover_s, s);

  // After the takeover, more commands: each reaches its robot exactly once, from the survivor.
  const uint64_t first_after_takeover = seq + 1;
  for (int round = 0; round < 5; ++round) {
    ASSERT_NO_FATAL_FAILURE(send_waypoints(++seq));
    std::this_thread::sleep_for(200ms);
  }
  ASSERT_TRUE(wait_until(
      [&] {
        size_t n = 0;
        for (const auto& [key, copies] : waypoints_received())
          n += key.second >= first_after_takeover ? 1 : 0;
        return n == kRobots * (seq - first_after_takeover + 1);
      },
      10s));
  // No command reached a robot twice, before, during or after the kill.
  for (const auto& [key, copies] : waypoints_received())
    EXPECT_EQ(copies, 1) << key.first << " waypoint seq " << key.second;

  // Robot messages during the kill: none twice; the ones lost are those mosquitto had handed to
  // the killed gateway and not seen acknowledged (not re-routed: mosquitto issue #2662).
  std::this_thread::sleep_for(1s);
  int64_t lost = 0;
  int64_t published = 0;
  for (int i = 0; i < kRobots; ++i) {
    for (int64_t m = first_load_marker; m <= last_marker; ++m) {
      ++published;
      const size_t copies = observation_count(robot_id(i), m);
      EXPECT_LE(copies, 1u) << robot_id(i) << " message " << m;
      lost += copies == 0 ? 1 : 0;
    }
  }
  std::printf(
      "[ figures ] takeover after kill -9: %.2f s (all %d robots served again); robot messages "
      "published during the kill phase: %lld, lost: %lld\n",
      takeover_s, kRobots, static_cast<long long>(published), static_cast<long long>(lost));
  RecordProperty("takeover_s", std::to_string(takeover_s));
  RecordProperty("messages_lost_in_kill", std::to_string(lost));
}

TEST_F(GatewayShareTest, EachViewerMqttRequestIsExecutedByOneGateway) {
  ASSERT_TRUE(wait_until([&] { return all_report("gateways_live", 2); }, 20s))
      << group.log("gw-a") << group.log("gw-b");
  testkit::MqttTestClient listener(port, "share-listener");
  ASSERT_EQ(listener.connect(), 0);
  ASSERT_TRUE(listener.subscribe("ops/share/#"));
  auto request_writer = testkit::make_test_writer(*participant, dds::kMqttRequest);
  // Retried until answered: a copy sent while the gateways warm up goes unanswered.
  auto requester = dds::Requester<MqttReply>::create(*participant, dds::kMqttReply, {200ms, 1000ms, 20s});
  ASSERT_TRUE(requester) << requester.message();
  constexpr int kRequests = 12;
  for (int i = 0; i < kRequests; ++i) {
    MqttRequest r;
    r.kind(MQTT_PUBLISH);
    r.topic("ops/share/" + std::to_string(i));
    r.payload({'x'});
    r.qos(1);
    const auto reply = (*requester)->call(*request_writer, r);
    ASSERT_TRUE(reply) << "request " << i << " unanswered\n" << group.log("gw-a") << group.log("gw-b");
    EXPECT_TRUE(reply->ok()) << reply->message();
  }
  std::this_thread::sleep_for(1s);  // a second copy would show up by now
  std::map<std::string, int> copies;
  for (const auto& m : listener.messages()) ++copies[m.topic];
  EXPECT_EQ(copies.size(), static_cast<size_t>(kRequests));
  for (const auto& [topic, n] : copies) EXPECT_EQ(n, 1) << topic;
  // Executed once in all: each gateway counts only the requests it ran.
  ASSERT_TRUE(wait_until(
      [&] {
        int64_t executed = 0;
        for (const auto& [instance, n] : counter("mqtt_requests")) executed += std::max<int64_t>(n, 0);
        return executed == kRequests;
      },
      5s));
}

}  // namespace
}  // namespace slam
