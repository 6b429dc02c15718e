// slam-simulator as a black box: it speaks the robot protocol over a real mosquitto (the test plays
// the server with a paho client) and Cyclone DDS to Fast DDS readers and writers (cross-vendor):
// a v1 robot drives to a waypoint and reports points on the true walls; ground truth, the world and
// the heartbeat reach Fast DDS; SimControl spawns robots; malformed commands leave the goal alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "mqtt_test_client.hpp"
#include "process_group.hpp"
#include "protocol/v1_codec.hpp"
#include "protocol/v2_robot_decode.hpp"
#include "protocol/v2_server_codec.hpp"
#include "simulator/core/builtin_worlds.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::wait_until;
using Bytes = std::vector<uint8_t>;

// The payload's bytes, as the protocol decoders take them.
std::span<const uint8_t> bytes_of(const std::string& payload) {
  return {reinterpret_cast<const uint8_t*>(payload.data()), payload.size()};
}

// The server side of MQTT for the test: a client connected to the simulator's broker.
std::unique_ptr<testkit::MqttTestClient> connect_test_client(int port) {
  auto client = std::make_unique<testkit::MqttTestClient>(port, "simulator_test");
  EXPECT_EQ(client->connect(), 0);
  return client;
}

protocol::DecodedObservation decode_adv(const std::string& payload) {
  protocol::DecodedObservation out;
  EXPECT_TRUE(protocol::decode_v1(bytes_of(payload), {}, out).is_ok());
  return out;
}

double wall_distance(const sim::World& world, protocol::Point p) {
  double best = INFINITY;
  for (const sim::Segment& s : world.walls())
    best = std::min(best, std::sqrt(sim::distance_sq({p.x, p.y}, s)));
  return best;
}

Bytes v1_waypoint(double x, double y) {
  std::array<uint8_t, protocol::kV1PairBytes> bytes{};
  EXPECT_TRUE(protocol::encode_v1_waypoint({x, y}, 100.0, bytes).is_ok());
  return Bytes(bytes.begin(), bytes.end());
}

// A simulator on its own broker and DDS domain, with a Fast DDS participant to watch it.
class SimulatorTest : public ::testing::Test {
 protected:
  void start(std::vector<std::string> extra) {
    port_ = group_.start_mosquitto();
    std::vector<std::string> argv = {testkit::bin_path("slam-simulator"),
                                     "--domain",
                                     std::to_string(domain_.id()),
                                     "--broker",
                                     "tcp://127.0.0.1:" + std::to_string(port_),
                                     "--world",
                                     "empty",
                                     "--seed",
                                     "7"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    group_.start("simulator", argv);
    mqtt_ = connect_test_client(port_);
    auto p = dds::Participant::create(domain_.id(), "simulator_test");
    ASSERT_TRUE(p) << p.message();
    participant_ = std::move(*p);
  }

  // Latest counter value from the simulator's Cyclone heartbeat, read with Fast DDS.
  void watch_heartbeat() {
    auto reader = dds::make_reader(*participant_, dds::kHeartbeat, [this](const Heartbeat& hb, const auto&) {
      if (hb.service() != "simulator") return;
      std::lock_guard lock(mutex_);
      for (const auto& c : hb.counters()) counters_[c.name().to_string()] = c.value();
      heartbeats_++;
    });
    ASSERT_TRUE(reader) << reader.message();
    heartbeat_reader_ = std::move(*reader);
  }
  int64_t counter(const std::string& name) {
    std::lock_guard lock(mutex_);
    const auto it = counters_.find(name);
    return it == counters_.end() ? -1 : it->second;
  }

  // Waits for the first adv of the single robot and returns its id.
  std::string first_robot_v1() {
    EXPECT_TRUE(mqtt_->subscribe("v1/robot/+/adv"));
    EXPECT_TRUE(wait_until([&] { return !mqtt_->messages().empty(); }, 20s)) << group_.log("simulator");
    const auto all = mqtt_->messages();
    if (all.empty()) return {};
    const std::string& t = all.front().topic;  // v1/robot/<id>/adv
    return t.substr(9, t.size() - 9 - 4);
  }

  bool arrives_v1(const std::string& id, double x, double y, std::chrono::milliseconds timeout) {
    return wait_until(
        [&] {
          const auto m = mqtt_->last("v1/robot/" + id + "/adv");
          if (!m) return false;
          const auto obs = decode_adv(m->payload);
          return std::hypot(obs.x - x, obs.y - y) < 0.07;
        },
        timeout, 50ms);
  }

  void TearDown() override {
    if (HasFailure()) std::cerr << "simulator log:\n" << group_.log("simulator") << "\n";
  }

  testkit::DomainLease domain_;
  testkit::ProcessGroup group_;
  int port_ = 0;
  std::unique_ptr<testkit::MqttTestClient> mqtt_;
  // Written by the listeners: declared before the readers so it outlives them (members are
  // destroyed in reverse order).
  std::mutex mutex_;
  std::map<std::string, int64_t> counters_;
  int heartbeats_ = 0;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader_;
};

TEST_F(SimulatorTest, V1RobotDrivesToWaypointAndSeesTheTrueWalls) {
  start({"--robots", "1", "--noise", "0.01", "--drift", "0", "--speed", "4"});
  const std::string id = first_robot_v1();
  ASSERT_FALSE(id.empty());
  // Standing still, believed and true pose agree: every point must lie on a wall within the noise
  // (5 sigma of 1 cm plus the centimetre rounding of v1).
  ASSERT_TRUE(wait_until([&] { return mqtt_->messages().size() >= 5; }, 10s));
  const auto world = sim::builtin_world("empty");
  ASSERT_TRUE(world);
  size_t points = 0;
  for (const auto& m : mqtt_->messages()) {
    const auto obs = decode_adv(m.payload);
    for (const auto& p : obs.hits) {
      EXPECT_LT(wall_distance(*world, p), 0.06) << "point (" << p.x << ", " << p.y << ")";
      ++points;
    }
  }
  EXPECT_GT(points, 10u);

  const auto start_pose = decode_adv(mqtt_->messages().back().payload);
  const double tx = start_pose.x < 5.0 ? 7.5 : 2.5;
  const double ty = start_pose.y < 5.0 ? 7.0 : 3.0;
  EXPECT_TRUE(mqtt_->publish("v1/server/" + id + "/cmd", v1_waypoint(tx, ty)));
  EXPECT_TRUE(arrives_v1(id, tx, ty, 30s))
      << "robot never reported a position near (" << tx << ", " << ty << ")";
}

TEST_F(SimulatorTest, StartOdomFrameReportsFromTheOriginAndTakesWaypointsInIt) {
  start({"--robots", "1", "--noise", "0", "--drift", "0", "--heading-drift", "0", "--odom-frame", "start",
         "--speed", "4"});
  const std::string id = first_robot_v1();
  ASSERT_FALSE(id.empty());
  const auto first = decode_adv(mqtt_->messages().front().payload);
  EXPECT_NEAR(first.x, 0.0, 0.011);
  EXPECT_NEAR(first.y, 0.0, 0.011);
  // Drive 0.5 m towards the farthest hit (open floor), given in the robot's own start frame.
  ASSERT_FALSE(first.hits.empty());
  const auto far = *std::max_element(first.hits.begin(), first.hits.end(), [](const auto& a, const auto& b) {
    return std::hypot(a.x, a.y) < std::hypot(b.x, b.y);
  });
  const double d = std::hypot(far.x, far.y);
  ASSERT_GT(d, 1.0);
  const double tx = 0.5 * far.x / d, ty = 0.5 * far.y / d;
  EXPECT_TRUE(mqtt_->publish("v1/server/" + id + "/cmd", v1_waypoint(tx, ty)));
  EXPECT_TRUE(arrives_v1(id, tx, ty, 30s)) << "robot never reported (" << tx << ", " << ty << ")";
}

TEST(SimulatorCli, OdometryFlagsAndTheRoomsWorldAreListedAndChecked) {
  testkit::ProcessGroup group;
  group.start("help", {testkit::bin_path("slam-simulator"), "--help"});
  ASSERT_EQ(group.wait_exit("help", 20s), 0);
  const std::string help = group.log("help");
  for (const char* word : {"--heading-drift", "--odom-frame", "rooms"})
    EXPECT_NE(help.find(word), std::string::npos) << word << " missing from --help:\n" << help;
  // {flag, value, what the one-line error names}; NaN passes CLI11's range and fails the config check.
  const std::vector<std::array<std::string, 3>> bad = {{"--heading-drift", "-0.1", "--heading-drift"},
                                                       {"--heading-drift", "nan", "drift_per_radian"},
                                                       {"--odom-frame", "map", "--odom-frame"}};
  for (size_t k = 0; k < bad.size(); ++k) {
    const auto& [flag, value, named] = bad[k];
    const std::string name = "bad" + std::to_string(k);
    group.start(name, {testkit::bin_path("slam-simulator"), flag, value});
    EXPECT_EQ(group.wait_exit(name, 20s), 2) << flag << " " << value << ": " << group.log(name);
    EXPECT_NE(group.log(name).find(named), std::string::npos) << group.log(name);
  }
}

TEST_F(SimulatorTest, GroundTruthWorldAndHeartbeatReachFastDds) {
  start({"--robots", "2"});
  std::mutex m;
  std::optional<SimWorld> world;
  std::optional<SimGroundTruth> truth;
  auto world_reader = dds::make_reader(*participant_, dds::kSimWorld, [&](const SimWorld& w, const auto&) {
    std::lock_guard lock(m);
    world = w;
  });
  ASSERT_TRUE(world_reader) << world_reader.message();
  auto truth_reader =
      dds::make_reader(*participant_, dds::kSimGroundTruth, [&](const SimGroundTruth& t, const auto&) {
        std::lock_guard lock(m);
        truth = t;
      });
  ASSERT_TRUE(truth_reader) << truth_reader.message();
  watch_heartbeat();

  // SimWorld is transient-local: this late reader still gets it.
  ASSERT_TRUE(wait_until(
      [&] {
        std::lock_guard lock(m);
        return world && truth;
      },
      30s));
  // Counters come from the Cyclone heartbeat; wait before taking `m`, which the listeners need.
  EXPECT_TRUE(wait_until([&] { return counter("robots") == 2; }, 10s))
      << "robots counter " << counter("robots");
  std::lock_guard lock(m);
  EXPECT_EQ(world->name(), "empty");
  EXPECT_DOUBLE_EQ(world->width_m(), 10.0);
  EXPECT_DOUBLE_EQ(world->height_m(), 10.0);
  EXPECT_EQ(world->walls().size(), 4u);
  ASSERT_EQ(truth->robots().size(), 2u);
  EXPECT_FALSE(truth->paused());
  EXPECT_GT(truth->stamp_ns(), 0);
  for (const auto& r : truth->robots()) {
    EXPECT_EQ(r.robot_id().to_string().rfind("sim-", 0), 0u) << r.robot_id().to_string();
    EXPECT_GT(r.true_pose().x(), 0.0);
    EXPECT_LT(r.true_pose().x(), 10.0);
  }
}

TEST_F(SimulatorTest, SimControlFromFastDdsSpawnsRobots) {
  start({"--robots", "1"});
  std::mutex m;
  size_t robots = 0;
  std::vector<std::string> ids;
  auto truth_reader =
      dds::make_reader(*participant_, dds::kSimGroundTruth, [&](const SimGroundTruth& t, const auto&) {
        std::lock_guard lock(m);
        robots = t.robots().size();
        ids.clear();
        for (const auto& r : t.robots()) ids.push_back(r.robot_id().to_string());
      });
  ASSERT_TRUE(truth_reader) << truth_reader.message();
  ASSERT_TRUE(wait_until(
      [&] {
        std::lock_guard lock(m);
        return robots == 1;
      },
      30s));
  watch_heartbeat();

  auto writer = dds::make_writer(*participant_, dds::kSimControl);
  ASSERT_TRUE(writer) << writer.message();
  ASSERT_TRUE((*writer)->wait_for_readers(20s));
  SimControl spawn;
  spawn.command_id(1);
  spawn.kind(SIM_SPAWN);
  spawn.count(2);
  // Each command is checked by its effect below (ground truth, counters), not by write()'s result.
  (*writer)->write(spawn);
  SimControl named;
  named.command_id(2);
  named.kind(SIM_SPAWN);
  Pose2 pose;
  pose.x(5.0);
  pose.y(5.0);
  named.poses().push_back(pose);
  named.robot_id("visitor");
  (*writer)->write(named);
  SimControl impossible;
  impossible.command_id(3);
  impossible.kind(SIM_SET_SPEED);
  impossible.speed_factor(-1.0);
  (*writer)->write(impossible);

  EXPECT_TRUE(wait_until(
      [&] {
        std::lock_guard lock(m);
        return robots == 4;
      },
      20s))
      << "robots: " << robots;
  {
    std::lock_guard lock(m);
    EXPECT_NE(std::find(ids.begin(), ids.end(), "visitor"), ids.end());
  }
  EXPECT_TRUE(
      wait_until([&] { return counter("controls_rejected") == 1 && counter("controls_applied") == 2; }, 10s))
      << "applied " << counter("controls_applied") << ", rejected " << counter("controls_rejected");
  // The new robots speak MQTT as well.
  EXPECT_TRUE(mqtt_->subscribe("v1/robot/visitor/adv"));
  EXPECT_TRUE(wait_until([&] { return mqtt_->last("v1/robot/visitor/adv").has_value(); }, 20s));
}

TEST_F(SimulatorTest, MalformedWaypointsAreIgnoredAndTheGoalKept) {
  start({"--robots", "1", "--drift", "0", "--speed", "2"});
  watch_heartbeat();
  const std::string id = first_robot_v1();
  ASSERT_FALSE(id.empty());
  const auto start_pose = decode_adv(mqtt_->messages().back().payload);
  const double tx = start_pose.x < 5.0 ? 8.0 : 2.0;
  const double ty = start_pose.y < 5.0 ? 8.0 : 2.0;
  const std::string cmd = "v1/server/" + id + "/cmd";
  EXPECT_TRUE(mqtt_->publish(cmd, v1_waypoint(tx, ty)));
  EXPECT_TRUE(mqtt_->publish(cmd, Bytes{0x01, 0x02, 0x03}));              // 3 bytes
  EXPECT_TRUE(mqtt_->publish(cmd, Bytes{0x64, 0x00, 0x64, 0x00, 0x64}));  // 5 bytes
  EXPECT_TRUE(mqtt_->publish(cmd, Bytes(8, 0x10)));                       // two pairs
  EXPECT_TRUE(mqtt_->publish(cmd, Bytes{}));                              // empty
  EXPECT_TRUE(mqtt_->publish(cmd, v1_waypoint(50.0, 50.0)));              // outside the 10 m world
  EXPECT_TRUE(wait_until([&] { return counter("waypoints_rejected") == 5; }, 15s))
      << "waypoints_rejected " << counter("waypoints_rejected");
  EXPECT_EQ(counter("waypoints_outside_world"), 1);
  EXPECT_TRUE(arrives_v1(id, tx, ty, 40s)) << "robot did not keep its goal (" << tx << ", " << ty << ")";
  EXPECT_TRUE(group_.running("simulator"));
}

TEST_F(SimulatorTest, MultiplexedV2RobotSendsScansAndFollowsJsonWaypoints) {
  start({"--robots", "1", "--protocol", "v2", "--mqtt-multiplex", "--drift", "0", "--speed", "4"});
  watch_heartbeat();
  EXPECT_TRUE(mqtt_->subscribe("v2/robot/+/+"));
  ASSERT_TRUE(wait_until([&] { return !mqtt_->messages().empty(); }, 20s));
  std::string id;
  ASSERT_TRUE(wait_until(
      [&] {
        for (const auto& msg : mqtt_->messages())
          if (msg.topic.ends_with("/scan")) id = msg.topic.substr(9, msg.topic.size() - 9 - 5);
        return !id.empty();
      },
      10s));
  const std::string scan_topic = "v2/robot/" + id + "/scan";
  protocol::DecodedObservation obs;
  ASSERT_TRUE(protocol::decode_v2_scan(bytes_of(mqtt_->last(scan_topic)->payload), {}, obs).is_ok());
  EXPECT_TRUE(obs.has_heading);
  EXPECT_EQ(obs.hits.size() + obs.misses.size(), 16u);
  EXPECT_GT(obs.robot_stamp_ns, 0) << "a v2 scan carries the robot's clock: the simulated time";
  EXPECT_TRUE(wait_until([&] { return mqtt_->last("v2/robot/" + id + "/status").has_value(); }, 10s));

  const std::string topic = "v2/server/" + id + "/waypoint";
  const double tx = obs.x < 5.0 ? 7.0 : 3.0;
  std::string good;
  ASSERT_TRUE(protocol::encode_v2_waypoint({1, {tx, 5.0}}, {}, good).is_ok());
  EXPECT_TRUE(mqtt_->publish(topic, good));
  EXPECT_TRUE(mqtt_->publish(topic, std::string("{\"seq\":2,\"x\":")));                // bad JSON
  EXPECT_TRUE(mqtt_->publish(topic, std::string("{\"seq\":3,\"x\":\"1\",\"y\":2}")));  // wrong type
  EXPECT_TRUE(wait_until(
      [&] {
        const auto m = mqtt_->last(scan_topic);
        protocol::DecodedObservation o;
        return m && protocol::decode_v2_scan(bytes_of(m->payload), {}, o).is_ok() &&
               std::hypot(o.x - tx, o.y - 5.0) < 0.07;
      },
      30s, 50ms));
  EXPECT_TRUE(wait_until([&] { return counter("waypoints_rejected") == 2; }, 10s));
}

TEST_F(SimulatorTest, ReconnectsAndResubscribesAfterBrokerRestart) {
  start({"--robots", "1", "--drift", "0", "--speed", "4"});
  watch_heartbeat();
  const std::string id = first_robot_v1();
  ASSERT_FALSE(id.empty());
  mqtt_.reset();
  group_.stop("mosquitto");
  group_.restart_mosquitto("mosquitto", port_);
  mqtt_ = connect_test_client(port_);
  EXPECT_TRUE(mqtt_->subscribe("v1/robot/+/adv"));
  ASSERT_TRUE(wait_until([&] { return mqtt_->last("v1/robot/" + id + "/adv").has_value(); }, 30s));
  EXPECT_TRUE(wait_until([&] { return counter("mqtt_reconnects") >= 1; }, 10s));
  // A command after the restart still arrives: the robot subscribed again.
  const auto pose = decode_adv(mqtt_->last("v1/robot/" + id + "/adv")->payload);
  const double tx = pose.x < 5.0 ? 7.0 : 3.0;
  EXPECT_TRUE(mqtt_->publish("v1/server/" + id + "/cmd", v1_waypoint(tx, 5.0)));
  EXPECT_TRUE(arrives_v1(id, tx, 5.0, 30s));
}

}  // namespace
}  // namespace slam
