// slam-gateway against a real mosquitto and real DDS readers/writers: robots speaking v1 (through
// mosquitto_pub/mosquitto_sub, as a 2019 robot's tooling would) and v2 (a paho client), a broker
// restart under a running gateway, and a flood of malformed messages beside a valid robot.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <fstream>
#include <initializer_list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "mqtt_test_client.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

// The value of a set-up Result, or a test failure and an empty value.
template <class T>
T take(Result<T> r) {
  if (!r) {
    ADD_FAILURE() << r.message();
    return T{};
  }
  return std::move(*r);
}

// DDS side of the test: what the gateway publishes, and waypoint commands to it.
class DdsProbe {
 public:
  explicit DdsProbe(int domain) {
    participant_ = take(dds::Participant::create(domain, "gateway-test"));
    observations_ = make_observation_reader(
        *participant_, [this](const RobotObservation& o) { keep(observations_seen_, o); });
    states_ = take(dds::make_reader(*participant_, dds::kRobotState,
                                    [this](const RobotState& s, const auto&) { keep(states_seen_, s); }));
    subscriptions_ = take(
        dds::make_reader(*participant_, dds::kMqttSubscriptions,
                         [this](const MqttSubscriptions& s, const auto&) { keep(subscriptions_seen_, s); }));
    heartbeats_ =
        take(dds::make_reader(*participant_, dds::kHeartbeat, [this](const Heartbeat& h, const auto&) {
          if (h.service() == std::string("gateway")) keep(heartbeats_seen_, h);
        }));
    waypoints_ = take(dds::make_writer(*participant_, dds::kWaypointCommand));
  }

  std::vector<RobotObservation> observations(const std::string& robot) {
    std::lock_guard lock(mutex_);
    std::vector<RobotObservation> out;
    for (const auto& o : observations_seen_)
      if (o.robot_id() == robot) out.push_back(o);
    return out;
  }
  std::optional<RobotState> latest_state(const std::string& robot) {
    std::lock_guard lock(mutex_);
    for (auto it = states_seen_.rbegin(); it != states_seen_.rend(); ++it)
      if (it->robot_id() == robot) return *it;
    return std::nullopt;
  }
  size_t state_count(const std::string& robot) {
    std::lock_guard lock(mutex_);
    return static_cast<size_t>(std::count_if(states_seen_.begin(), states_seen_.end(),
                                             [&](const RobotState& s) { return s.robot_id() == robot; }));
  }
  bool connected() {
    std::lock_guard lock(mutex_);
    return !subscriptions_seen_.empty() && subscriptions_seen_.back().connected();
  }
  size_t subscription_samples() {
    std::lock_guard lock(mutex_);
    return subscriptions_seen_.size();
  }
  // Latest value of a gateway heartbeat counter; -1 before any heartbeat named it.
  int64_t counter(const std::string& name) {
    std::lock_guard lock(mutex_);
    if (heartbeats_seen_.empty()) return -1;
    for (const auto& c : heartbeats_seen_.back().counters())
      if (c.name() == name) return c.value();
    return -1;
  }
  void send_waypoint(const std::string& robot, uint64_t seq, double x, double y,
                     std::vector<Point2> rest = {}) {
    WaypointCommand c;
    c.robot_id(robot);
    c.seq(seq);
    c.waypoint().x(x);
    c.waypoint().y(y);
    c.remaining(std::move(rest));
    waypoints_->write(c);
  }
  bool waypoint_reader_matched() { return waypoints_->matched_readers() > 0; }

 private:
  template <class T>
  void keep(std::vector<T>& into, const T& sample) {
    std::lock_guard lock(mutex_);
    into.push_back(sample);
  }

  std::mutex mutex_;
  std::vector<RobotObservation> observations_seen_;
  std::vector<RobotState> states_seen_;
  std::vector<MqttSubscriptions> subscriptions_seen_;
  std::vector<Heartbeat> heartbeats_seen_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Reader<RobotObservationBatch>> observations_;
  std::unique_ptr<dds::Reader<RobotState>> states_;
  std::unique_ptr<dds::Reader<MqttSubscriptions>> subscriptions_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeats_;
  std::unique_ptr<dds::Writer<WaypointCommand>> waypoints_;
};

std::string hex_bytes(const std::string& hex) {
  std::string out;
  for (size_t i = 0; i + 1 < hex.size(); i += 2)
    out += static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16));
  return out;
}

class GatewayTest : public ::testing::Test {
 protected:
  void start_gateway(std::vector<std::string> extra = {}) {
    std::vector<std::string> argv{bin_path("slam-gateway"),
                                  "--domain",
                                  std::to_string(domain.id()),
                                  "--broker",
                                  "tcp://127.0.0.1:" + std::to_string(port),
                                  "--reconnect-max-s",
                                  "1",
                                  "--log-level",
                                  "debug",
                                  "--no-share"};  // a lone gateway: waypoints go out from its start
    argv.insert(argv.end(), extra.begin(), extra.end());
    group.start("gateway", argv);
    ASSERT_TRUE(wait_until([&] { return probe.connected(); }, 20s))
        << "gateway never reported an MQTT connection";
    ASSERT_TRUE(wait_until([&] { return probe.waypoint_reader_matched(); }, 10s));
  }
  // Publishes a v1 report as each robot of `ids` until the gateway has an observation of every one on
  // DDS: the gateway reports its connection before the broker has acknowledged its subscriptions.
  void report_until_seen(MqttTestClient& client, std::initializer_list<const char*> ids) {
    ASSERT_TRUE(wait_until(
        [&] {
          bool all = true;
          for (const char* id : ids) {
            client.publish(std::string("v1/robot/") + id + "/adv", hex_bytes("64000000"), 0);
            all = all && !probe.observations(id).empty();
          }
          return all;
        },
        10s, 100ms))
        << group.log("gateway");
  }
  // Publishes a v1 adv payload from a file with mosquitto_pub, as a legacy robot's tooling would.
  void mosquitto_pub_file(const std::string& name, const std::string& topic, const std::string& payload) {
    const std::string file = group.dir() + "/" + name + ".bin";
    std::ofstream(file, std::ios::binary) << payload;
    group.start(name, {"mosquitto_pub", "-p", std::to_string(port), "-q", "1", "-t", topic, "-f", file});
    ASSERT_EQ(group.wait_exit(name, 10s), 0) << group.log(name);
  }

  DomainLease domain;
  ProcessGroup group;
  int port = group.start_mosquitto();
  DdsProbe probe{domain.id()};
};

TEST(GatewayCliTest, HelpExitsZeroAndBadConfigExitsTwoWithOneLine) {
  ProcessGroup group;
  group.start("help", {bin_path("slam-gateway"), "--help"});
  EXPECT_EQ(group.wait_exit("help", 10s), 0);
  EXPECT_NE(group.log("help").find("--broker"), std::string::npos);

  group.start("qos", {bin_path("slam-gateway"), "--qos", "3"});
  EXPECT_EQ(group.wait_exit("qos", 10s), 2);
  const std::string qos = group.log("qos");
  EXPECT_NE(qos.find("qos must be 0, 1 or 2"), std::string::npos) << qos;
  EXPECT_EQ(std::count(qos.begin(), qos.end(), '\n'), 1) << qos;

  const std::string config = group.dir() + "/bad.yaml";
  std::ofstream(config) << "broker: http://nowhere\n";
  group.start("config", {bin_path("slam-gateway"), "--config", config});
  EXPECT_EQ(group.wait_exit("config", 10s), 2);
  const std::string bad = group.log("config");
  EXPECT_NE(bad.find("broker"), std::string::npos) << bad;
  EXPECT_EQ(std::count(bad.begin(), bad.end(), '\n'), 1) << bad;
}

TEST_F(GatewayTest, V1RobotObservationInMetresAndWaypointAsExactlyFourBytes) {
  ASSERT_NO_FATAL_FAILURE(start_gateway());
  // (100, -250) position and (120, 35) obstacle, centimetres.
  ASSERT_NO_FATAL_FAILURE(mosquitto_pub_file("pub1", "v1/robot/r1/adv", hex_bytes("640006ff78002300")));
  ASSERT_TRUE(wait_until([&] { return !probe.observations("r1").empty(); }, 10s)) << group.log("gateway");
  const RobotObservation o = probe.observations("r1").front();
  EXPECT_EQ(o.seq(), 1u);
  EXPECT_EQ(o.protocol(), PROTOCOL_V1);
  EXPECT_DOUBLE_EQ(o.pose().x(), 1.0);
  EXPECT_DOUBLE_EQ(o.pose().y(), -2.5);
  EXPECT_FALSE(o.has_heading());
  ASSERT_EQ(o.hits().size(), 1u);
  EXPECT_DOUBLE_EQ(o.hits()[0].x(), 1.2);
  EXPECT_DOUBLE_EQ(o.hits()[0].y(), 0.35);
  EXPECT_TRUE(o.misses().empty());
  ASSERT_TRUE(wait_until([&] { return probe.latest_state("r1").has_value(); }, 5s));
  EXPECT_EQ(probe.latest_state("r1")->presence(), PRESENCE_ONLINE);
  EXPECT_EQ(probe.latest_state("r1")->messages(), 1u);

  group.start("sub",
              {"mosquitto_sub", "-p", std::to_string(port), "-C", "1", "-F", "%x", "-t", "v1/server/r1/cmd"});
  // The planner re-sends every second; here the test does, until mosquitto_sub has subscribed and got one.
  uint64_t seq = 0;
  ASSERT_TRUE(wait_until(
      [&] {
        probe.send_waypoint("r1", ++seq, 1.0, -2.5);
        return !group.running("sub");
      },
      10s, 200ms))
      << group.log("gateway");
  EXPECT_EQ(group.log("sub"), "640006ff\n");

  // Beyond int16 at 100 units/m: counted, never sent wrapped.
  MqttTestClient robot(port, "r1-listener");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_TRUE(robot.subscribe("v1/server/r1/cmd"));
  probe.send_waypoint("r1", ++seq, 400.0, 0.0);
  ASSERT_TRUE(wait_until([&] { return probe.counter("commands_failed") >= 1; }, 5s));
  EXPECT_FALSE(robot.next(500ms).has_value());
}

TEST_F(GatewayTest, V2PoseScanStatusInWaypointAndPathOut) {
  ASSERT_NO_FATAL_FAILURE(start_gateway());
  MqttTestClient robot(port, "r2");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_TRUE(robot.subscribe("v2/server/r2/+"));
  ASSERT_TRUE(robot.publish("v2/robot/r2/pose", R"({"x": 1.5, "y": -2.0, "heading": 0.3})"));
  ASSERT_TRUE(robot.publish("v2/robot/r2/scan", R"({"pose": {"x": 1.0, "y": 2.0, "heading": 0.0},
      "angles": [0.0, 1.5707963267948966], "ranges": [1.0, null], "max_range": 4.0})"));
  ASSERT_TRUE(robot.publish("v2/robot/r2/status", R"({"battery": 0.82, "state": "exploring"})"));
  ASSERT_TRUE(wait_until([&] { return probe.observations("r2").size() == 2; }, 10s)) << group.log("gateway");
  const auto obs = probe.observations("r2");
  EXPECT_EQ(obs[0].seq(), 1u);
  EXPECT_EQ(obs[0].protocol(), PROTOCOL_V2);
  EXPECT_TRUE(obs[0].has_heading());
  EXPECT_DOUBLE_EQ(obs[0].pose().theta(), 0.3);
  EXPECT_EQ(obs[1].seq(), 2u);
  ASSERT_EQ(obs[1].hits().size(), 1u);
  EXPECT_NEAR(obs[1].hits()[0].x(), 2.0, 1e-9);
  EXPECT_NEAR(obs[1].hits()[0].y(), 2.0, 1e-9);
  ASSERT_EQ(obs[1].misses().size(), 1u);
  EXPECT_NEAR(obs[1].misses()[0].x(), 1.0, 1e-9);
  EXPECT_NEAR(obs[1].misses()[0].y(), 6.0, 1e-9);
  ASSERT_TRUE(wait_until(
      [&] {
        auto s = probe.latest_state("r2");
        return s && s->status() == std::string("exploring");
      },
      5s));
  EXPECT_FLOAT_EQ(probe.latest_state("r2")->battery(), 0.82f);
  EXPECT_EQ(probe.latest_state("r2")->protocol(), PROTOCOL_V2);

  Point2 next;
  next.x(3.0);
  next.y(0.25);
  probe.send_waypoint("r2", 7, 1.5, -2.0, {next});
  std::map<std::string, std::string> got;
  while (got.size() < 2) {
    auto m = robot.next(5s);
    ASSERT_TRUE(m.has_value()) << group.log("gateway");
    got[m->topic] = m->payload;
  }
  EXPECT_EQ(got["v2/server/r2/waypoint"], R"({"seq":7,"x":1.5,"y":-2})");
  EXPECT_EQ(got["v2/server/r2/path"], R"({"seq":7,"points":[[1.5,-2],[3,0.25]]})");

  // The last will marks the robot offline at once, long before --offline-after-s.
  ASSERT_TRUE(robot.publish("v2/robot/r2/status", R"({"state": "offline"})"));
  ASSERT_TRUE(wait_until(
      [&] {
        auto s = probe.latest_state("r2");
        return s && s->presence() == PRESENCE_OFFLINE;
      },
      3s));
}

TEST_F(GatewayTest, BrokerRestartResumesTrafficWithoutRestartingTheGateway) {
  ASSERT_NO_FATAL_FAILURE(start_gateway());
  {
    MqttTestClient robot(port, "before");
    ASSERT_EQ(robot.connect(), 0);
    ASSERT_TRUE(robot.publish("v1/robot/rb/adv", hex_bytes("0a001400")));
  }
  ASSERT_TRUE(wait_until([&] { return probe.observations("rb").size() == 1; }, 10s));

  group.stop("mosquitto");
  ASSERT_TRUE(wait_until([&] { return !probe.connected(); }, 10s)) << "disconnection not reported";
  group.restart_mosquitto("mosquitto", port);
  ASSERT_TRUE(wait_until([&] { return probe.connected(); }, 15s)) << group.log("gateway");
  EXPECT_TRUE(group.running("gateway"));

  // Re-subscribed (clean session): messages flow again, and commands go out again.
  MqttTestClient robot(port, "after");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_TRUE(robot.subscribe("v1/server/rb/cmd"));
  ASSERT_TRUE(wait_until(
      [&] {
        robot.publish("v1/robot/rb/adv", hex_bytes("0a001400"));
        return probe.observations("rb").size() >= 2;
      },
      10s, 250ms))
      << group.log("gateway");
  EXPECT_EQ(probe.observations("rb")[1].seq(), 2u) << "per-robot sequence survives the broker restart";
  probe.send_waypoint("rb", 1, 0.1, 0.2);
  auto cmd = robot.next(5s);
  ASSERT_TRUE(cmd.has_value());
  EXPECT_EQ(cmd->payload, hex_bytes("0a001400"));
  ASSERT_TRUE(wait_until([&] { return probe.counter("reconnects") >= 1; }, 5s));
}

// The loop wakes for the fleet digest every 0.1 s; a longer state period must still hold per robot.
TEST_F(GatewayTest, RobotStatesFollowTheStatePeriodNotTheLoopsOtherWakes) {
  ASSERT_NO_FATAL_FAILURE(start_gateway({"--state-period-s", "5"}));
  MqttTestClient robot(port, "steady");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_NO_FATAL_FAILURE(report_until_seen(robot, {"steady"}));
  // 30 moving reports over ~1.5 s: the first sighting goes out at once, the rest wait for the period.
  for (int i = 1; i <= 30; ++i) {
    const auto x = static_cast<char>(100 + i);
    ASSERT_TRUE(robot.publish("v1/robot/steady/adv", std::string{x, 0, 0, 0}, 0));
    std::this_thread::sleep_for(50ms);
  }
  ASSERT_TRUE(wait_until([&] { return probe.observations("steady").size() >= 31; }, 10s));
  EXPECT_LE(probe.state_count("steady"), 2u) << group.log("gateway");
}

TEST_F(GatewayTest, AnObservationWaitsForItsBatchTimeNotForTheLoopsNextWake) {
  // Nothing else wakes the loop for 10 s: a batch still leaves after --batch-ms.
  ASSERT_NO_FATAL_FAILURE(start_gateway({"--state-period-s", "10", "--digest-period-s", "30",
                                         "--digest-points-period-s", "30", "--batch-ms", "20"}));
  MqttTestClient robot(port, "lone");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_NO_FATAL_FAILURE(report_until_seen(robot, {"lone"}));
  std::this_thread::sleep_for(500ms);  // the first sighting's wake is over; the loop sleeps for 10 s
  for (int i = 1; i <= 3; ++i) {
    const size_t seen = probe.observations("lone").size();
    ASSERT_TRUE(robot.publish("v1/robot/lone/adv", std::string{static_cast<char>(100 + i), 0, 0, 0}, 0));
    EXPECT_TRUE(wait_until([&] { return probe.observations("lone").size() > seen; }, 3s))
        << "observation " << i << " waited for the loop's next wake";
  }
}

TEST_F(GatewayTest, ABurstSharesSamplesAndKeepsEachRobotsOrder) {
  ASSERT_NO_FATAL_FAILURE(start_gateway());
  MqttTestClient robots(port, "burst");
  ASSERT_EQ(robots.connect(), 0);
  ASSERT_NO_FATAL_FAILURE(report_until_seen(robots, {"a", "b"}));
  const size_t warmup_a = probe.observations("a").size(), warmup_b = probe.observations("b").size();
  constexpr int kEach = 200;
  for (int i = 0; i < kEach; ++i) {
    const auto x = static_cast<char>(i % 100);
    // QoS 0: no wait for the broker's acknowledgement, so the messages come as one burst.
    ASSERT_TRUE(robots.publish("v1/robot/a/adv", std::string{x, 0, 0, 0}, 0));
    ASSERT_TRUE(robots.publish("v1/robot/b/adv", std::string{x, 1, 0, 0}, 0));
  }
  ASSERT_TRUE(wait_until(
      [&] {
        return probe.observations("a").size() >= warmup_a + kEach &&
               probe.observations("b").size() >= warmup_b + kEach;
      },
      20s))
      << probe.observations("a").size() << " and " << probe.observations("b").size() << " observations";
  for (const char* id : {"a", "b"}) {
    const std::vector<RobotObservation> seen = probe.observations(id);
    for (size_t k = 1; k < seen.size(); ++k)
      ASSERT_EQ(seen[k].seq(), seen[k - 1].seq() + 1) << "robot " << id << " observation " << k;
  }
  // Several observations to a DDS sample: fewer batches than observations.
  ASSERT_TRUE(wait_until([&] { return probe.counter("observations") >= 2 * kEach; }, 10s));
  EXPECT_LT(probe.counter("observation_batches"), probe.counter("observations") / 2);
}

TEST_F(GatewayTest, MalformedFloodLeavesAValidRobotUnaffected) {
  ASSERT_NO_FATAL_FAILURE(start_gateway());
  MqttTestClient attacker(port, "attacker");
  ASSERT_EQ(attacker.connect(), 0);
  MqttTestClient robot(port, "good");
  ASSERT_EQ(robot.connect(), 0);
  // The flood starts once a robot message gets through, or the first good messages could go nowhere.
  ASSERT_NO_FATAL_FAILURE(report_until_seen(robot, {"warmup"}));

  const std::vector<std::pair<std::string, std::string>> bad{
      {"v1/robot/bad/adv", "abc"},                       // bad_length
      {"v1/robot/bad/adv", ""},                          // empty_payload
      {"v2/robot/bad/pose", "{\"x\": 1"},                // json_syntax
      {"v2/robot/bad/pose", R"({"x": "1", "y": 0})"},    // json_type
      {"v2/robot/bad/pose", R"({"y": 0})"},              // missing_field
      {"v2/robot/bad/pose", R"({"x": 1e999, "y": 0})"},  // non_finite
      {"v2/robot/bad/pose", R"({"x": 1e6, "y": 0})"},    // out_of_range
      {"v2/robot/bad/status", R"({"state": ""})"},       // bad_text
      {"v2/robot/bad/Pose", "{}"},                       // unknown_topic
      {"v2/robot/*/pose", R"({"x": 1, "y": 0})"},        // bad_robot_id ('*' means every robot)
  };
  constexpr int kRounds = 300;  // 3000 bad messages
  constexpr int kGood = 50;
  for (int i = 0; i < kRounds; ++i) {
    // QoS 0: as fast as the socket takes them (paho's synchronous QoS 1 waits ~100 ms per message).
    for (const auto& [topic, payload] : bad) ASSERT_TRUE(attacker.publish(topic, payload, 0)) << topic;
    if (i % (kRounds / kGood) == 0) {
      ASSERT_TRUE(robot.publish("v1/robot/good/adv", hex_bytes("64000000")));
    }
  }
  ASSERT_TRUE(wait_until([&] { return probe.observations("good").size() == kGood; }, 20s))
      << "valid robot got " << probe.observations("good").size() << " of " << kGood << "\n"
      << group.log("gateway");
  const auto good = probe.observations("good");
  for (size_t i = 0; i < good.size(); ++i) EXPECT_EQ(good[i].seq(), i + 1);
  EXPECT_TRUE(probe.observations("bad").empty());

  ASSERT_TRUE(wait_until([&] { return probe.counter("rejected_bad_robot_id") == kRounds; }, 10s))
      << group.log("gateway");
  for (const char* name : {"rejected_bad_length", "rejected_empty_payload", "rejected_json_syntax",
                           "rejected_json_type", "rejected_missing_field", "rejected_non_finite",
                           "rejected_out_of_range", "rejected_bad_text", "rejected_unknown_topic"}) {
    EXPECT_EQ(probe.counter(name), kRounds) << name;
  }
  EXPECT_EQ(probe.counter("rejected_oversized"), 0);
  EXPECT_EQ(probe.counter("rejected_too_many_points"), 0);
  EXPECT_GE(probe.counter("messages_in"), kRounds * 10 + kGood);
  // Rate-limited: a few lines per robot and reason, not thousands.
  const std::string log = group.log("gateway");
  size_t lines = 0;
  for (size_t at = log.find("rejected "); at != std::string::npos; at = log.find("rejected ", at + 1))
    ++lines;
  EXPECT_LT(lines, 200u);
  EXPECT_NE(log.find("bad_length: payload is 3 bytes"), std::string::npos);
  EXPECT_TRUE(group.running("gateway"));
}

}  // namespace
}  // namespace slam::testkit
