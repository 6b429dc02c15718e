// slam-simulator --play as a black box: a small CARMEN log written here is played through a real
// mosquitto, and what arrives is read back with the gateway's own v2 decoder: one scan per log
// scan with the odometry pose, the laser mount as sensor offset, hits and misses as the log says,
// the log's stamps; pieces become robots; the player prints the log's stats and exits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "mqtt_test_client.hpp"
#include "process_group.hpp"
#include "protocol/v2_robot_decode.hpp"
#include "temp_dir.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::wait_until;

constexpr double kPi = std::numbers::pi;

// Four beams at -90, -45, 0 and 45 degrees read 1, 2, nothing (81.91) and 3 m; the laser sits 0.1 m
// ahead of the robot. Line 5 is junk (a scan without a usable odometry pose), the scan stamped
// 10.1 steps back.
constexpr const char* kLog =
    "# a small CARMEN log\n"
    "PARAM robot_frontlaser_offset 0.1 host 0\n"
    "FLASER 4 1.0 2.0 81.91 3.0 0.1 0 0 0 0 0 10.0 host 10.0\n"
    "ODOM 0.5 0 0.2 0 0 0 10.1 host 10.1\n"
    "FLASER 4 1.0 2.0 81.91 3.0 0 0 0 nan 0 0 10.1 host 10.1\n"
    "FLASER 4 1.0 2.0 81.91 3.0 1.1 0 0.5 1 0 0.5 10.2 host 10.2\n"
    "FLASER 4 1.0 2.0 81.91 3.0 2.1 0 1 2 0 1 10.1 host 10.1\n"
    "FLASER 4 1.0 2.0 81.91 3.0 3.1 0 1 3 0 1 10.4 host 10.4\n";

struct Expected {
  double x, theta, stamp;
};
const Expected kScans[] = {{0, 0, 10.0}, {1, 0.5, 10.2}, {2, 1, 10.1}, {3, 1, 10.4}};

std::span<const uint8_t> bytes_of(const std::string& payload) {
  return {reinterpret_cast<const uint8_t*>(payload.data()), payload.size()};
}

class SimulatorPlayTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "corridor.clf") << kLog;
    port_ = group_.start_mosquitto();
    mqtt_ = std::make_unique<testkit::MqttTestClient>(port_, "simulator_play_test");
    ASSERT_EQ(mqtt_->connect(), 0);
    ASSERT_TRUE(mqtt_->subscribe("v2/robot/+/+"));
  }

  // Plays with `extra` flags, waits for the player to exit 0 and returns its output.
  std::string play(std::vector<std::string> extra) {
    std::vector<std::string> argv = {testkit::bin_path("slam-simulator"), "--broker",
                                     "tcp://127.0.0.1:" + std::to_string(port_)};
    argv.insert(argv.end(), extra.begin(), extra.end());
    group_.start("player", argv);
    EXPECT_EQ(group_.wait_exit("player", 30s), 0) << group_.log("player");
    return group_.log("player");
  }

  // The decoded scans each robot sent, in arrival order, once `count` scans have arrived.
  std::map<std::string, std::vector<protocol::DecodedObservation>> scans(size_t count) {
    const auto is_scan = [](const testkit::MqttMessage& m) { return m.topic.ends_with("/scan"); };
    EXPECT_TRUE(wait_until(
        [&] {
          const auto all = mqtt_->messages();
          return static_cast<size_t>(std::count_if(all.begin(), all.end(), is_scan)) >= count;
        },
        10s));
    std::map<std::string, std::vector<protocol::DecodedObservation>> out;
    for (const auto& m : mqtt_->messages()) {
      if (!is_scan(m)) continue;
      protocol::DecodedObservation obs;
      const auto s = protocol::decode_v2_scan(bytes_of(m.payload), {}, obs);
      EXPECT_TRUE(s.is_ok()) << s.detail() << ": " << m.payload;
      out[m.topic.substr(9, m.topic.size() - 9 - 5)].push_back(obs);
    }
    return out;
  }

  testkit::TempDir dir_{"simulator-play"};
  testkit::ProcessGroup group_;
  int port_ = 0;
  std::unique_ptr<testkit::MqttTestClient> mqtt_;
};

TEST_F(SimulatorPlayTest, EveryScanArrivesAsAV2ScanFromTheRecordedPose) {
  const std::string out = play({"--play", (dir_ / "corridor.clf").string(), "--play-rate", "0"});
  EXPECT_NE(out.find("4 scans, 1 odometry, 8 lines; 1 bad lines, 1 stamps back"), std::string::npos) << out;
  EXPECT_NE(out.find("(first bad: line 5: FLASER"), std::string::npos) << out;
  EXPECT_NE(out.find("done: 4/4 scans sent (100%)"), std::string::npos) << out;

  const auto by_robot = scans(4);
  ASSERT_EQ(by_robot.size(), 1u);
  const auto& sent = by_robot.at("corridor");
  ASSERT_EQ(sent.size(), 4u);
  for (size_t i = 0; i < sent.size(); ++i) {
    SCOPED_TRACE(i);
    const auto& obs = sent[i];
    const Expected& e = kScans[i];
    // The observation's pose is the sensor origin: 0.1 m ahead of the robot.
    EXPECT_NEAR(obs.x, e.x + 0.1 * std::cos(e.theta), 1e-9);
    EXPECT_NEAR(obs.y, 0.1 * std::sin(e.theta), 1e-9);
    EXPECT_NEAR(obs.theta, e.theta, 1e-9);
    EXPECT_NEAR(static_cast<double>(obs.robot_stamp_ns), e.stamp * 1e9, 1e3);  // the log's clock
    ASSERT_EQ(obs.hits.size(), 3u);
    ASSERT_EQ(obs.misses.size(), 1u);
    // The beam at -90 degrees read 1 m; the one at 0 saw nothing up to 81 m, which the decoder reads as
    // free space up to the gateway's scan_free_range_m.
    EXPECT_NEAR(obs.hits[0].x, obs.x + std::cos(e.theta - kPi / 2), 1e-4);
    EXPECT_NEAR(obs.hits[0].y, obs.y + std::sin(e.theta - kPi / 2), 1e-4);
    const double free_range = protocol::CodecLimits{}.scan_free_range_m;
    EXPECT_NEAR(obs.misses[0].x, obs.x + free_range * std::cos(e.theta), 1e-4);
    EXPECT_NEAR(obs.misses[0].y, obs.y + free_range * std::sin(e.theta), 1e-4);
  }
  // A v2 robot says what it is doing, and "offline" when it stops.
  const auto status = mqtt_->wait_for("v2/robot/corridor/status", 5s);
  ASSERT_TRUE(status);
  EXPECT_TRUE(wait_until(
      [&] { return mqtt_->last("v2/robot/corridor/status")->payload.find("offline") != std::string::npos; },
      5s));
}

TEST_F(SimulatorPlayTest, PiecesThinningAndClippingMakeRobotsAndBeams) {
  std::ofstream(dir_ / "second.clf") << kLog;
  play({"--play", (dir_ / "corridor.clf").string(), "--play", (dir_ / "second.clf").string(),
        "--play-robot-id", "a", "--play-robot-id", "b", "--play-pieces", "2", "--play-rate", "20",
        "--play-beams", "2", "--play-max-range", "2.5"});
  const auto by_robot = scans(8);
  ASSERT_EQ(by_robot.size(), 4u);
  for (const char* id : {"a-1", "a-2", "b-1", "b-2"}) {
    ASSERT_TRUE(by_robot.contains(id)) << id;
    const auto& sent = by_robot.at(id);
    ASSERT_EQ(sent.size(), 2u) << id;
    // Two beams, the centres of two sectors: -45 degrees (2 m, a hit) and 45 degrees (3 m, beyond
    // the 2.5 m clip: a miss at 2.5 m).
    for (const auto& obs : sent) {
      ASSERT_EQ(obs.hits.size(), 1u);
      ASSERT_EQ(obs.misses.size(), 1u);
      EXPECT_NEAR(std::hypot(obs.hits[0].x - obs.x, obs.hits[0].y - obs.y), 2.0, 1e-4);
      EXPECT_NEAR(std::hypot(obs.misses[0].x - obs.x, obs.misses[0].y - obs.y), 2.5, 1e-4);
    }
  }
  EXPECT_NEAR(by_robot.at("a-2")[0].theta, 1.0, 1e-9);  // the second piece starts at the third scan
}

TEST(SimulatorPlayCli, BadLogsAndFlagsAreOneLineErrors) {
  testkit::ProcessGroup group;
  testkit::TempDir dir("simulator-play");
  std::ofstream(dir / "empty.clf") << "# nothing\n";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--play", (dir / "missing.clf").string()}, "cannot open"},
      {{"--play", (dir / "empty.clf").string()}, "no scans"},
      {{"--play", (dir / "empty.clf").string(), "--play-start", "5", "--play-end", "2"},
       "--play-end 2 is not after"},
      {{"--play-robot-id", "r"}, "--play-robot-id needs --play"},
  };
  for (size_t k = 0; k < cases.size(); ++k) {
    const auto& [args, named] = cases[k];
    std::vector<std::string> argv = {testkit::bin_path("slam-simulator")};
    argv.insert(argv.end(), args.begin(), args.end());
    const std::string name = "case" + std::to_string(k);
    group.start(name, argv);
    EXPECT_NE(group.wait_exit(name, 20s), 0) << named;
    EXPECT_NE(group.log(name).find(named), std::string::npos) << group.log(name);
  }
}

}  // namespace
}  // namespace slam
