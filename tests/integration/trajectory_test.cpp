// Robot time end to end and `slamctl trajectory`: a v2 robot's "stamp" crosses the gateway into
// RobotObservation.robot_stamp_ns and the mapper's store, and the mapper writes the robot's
// trajectory with the robot's own stamps (TUM by default, CARMEN on request); an unknown robot and an
// unwritable path fail with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

constexpr const char* kRobot = "stamped-1";

// One v2 scan of robot time `stamp` seconds, the robot at (x, 0) facing +x, one beam hitting 1 m ahead.
std::string scan_at(double x, double stamp) {
  std::ostringstream json;
  json << R"({"pose": {"x": )" << x << R"(, "y": 0, "heading": 0}, "angle_min": 0, "angle_increment": 0.1, )"
       << R"("ranges": [1.0], "max_range": 4, "stamp": )" << stamp << "}";
  return json.str();
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class TrajectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string d = std::to_string(domain.id());
    group.start("gateway", {bin_path("slam-gateway"), "--domain", d, "--broker",
                            "tcp://127.0.0.1:" + std::to_string(port), "--no-share"});
    // SLAM off: every observation is stored as it arrives, placed by the identity.
    group.start("mapper", {bin_path("slam-mapper"), "--domain", d, "--store", group.dir() + "/map.db",
                           "--slam", "off"});
    auto p = dds::Participant::create(domain.id(), "trajectory-test");
    if (!p) throw std::runtime_error(p.message());
    participant = std::move(*p);
    reader = make_observation_inbox_reader(*participant, observations);
    heartbeat_reader = make_inbox_reader(*participant, dds::kHeartbeat, heartbeats);
    ASSERT_EQ(robot.connect(), 0);
    // The mapper starts 2.5 s late (one mapper per domain) and the gateway says it is connected
    // before the broker has its subscription: a warm-up robot reports until the mapper has
    // integrated one of its messages.
    ASSERT_TRUE(wait_until(
        [&] {
          robot.publish("v2/robot/warm-up/pose", std::string_view(R"({"x": 0, "y": 0})"), 0);
          return mapper_observations() > 0;
        },
        30s, 100ms))
        << group.log("gateway") << group.log("mapper");
  }
  void TearDown() override {
    if (!HasFailure()) return;
    for (const char* s : {"gateway", "mapper"}) std::cerr << s << " log:\n" << group.log(s) << "\n";
  }

  // slamctl with `args`: exit code, and its output (stdout and stderr).
  std::pair<int, std::string> ctl(std::vector<std::string> args) {
    const std::string name = "slamctl" + std::to_string(++runs);
    std::vector<std::string> argv{bin_path("slamctl"), "--domain", std::to_string(domain.id()), "--timeout",
                                  "10"};
    argv.insert(argv.end(), args.begin(), args.end());
    group.start(name, argv);
    const int code = group.wait_exit(name, 60s);
    return {code, group.log(name)};
  }

  // The mapper's `observations` counter in its latest heartbeat.
  int64_t mapper_observations() const {
    const auto beat = heartbeats.last([](const Heartbeat& h) { return h.service().to_string() == "mapper"; });
    if (!beat) return 0;
    for (const Counter& c : beat->counters())
      if (c.name().to_string() == "observations") return c.value();
    return 0;
  }

  std::vector<RobotObservation> seen_of(const std::string& id) const {
    std::vector<RobotObservation> out;
    for (const RobotObservation& o : observations.items())
      if (o.robot_id().to_string() == id) out.push_back(o);
    return out;
  }

  DomainLease domain;
  ProcessGroup group;
  int port = group.start_mosquitto();
  MqttTestClient robot{port, "trajectory-test-robot"};
  Inbox<RobotObservation> observations;
  Inbox<Heartbeat> heartbeats;
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Reader<RobotObservationBatch>> reader;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader;
  int runs = 0;
};

TEST_F(TrajectoryTest, TheMapperWritesTheRobotsTrajectoryWithTheRobotsOwnStamps) {
  const std::vector<double> stamps{100.0, 100.25, 100.5, 100.75, 101.0};
  for (size_t i = 0; i < stamps.size(); ++i)
    ASSERT_TRUE(robot.publish(std::string("v2/robot/") + kRobot + "/scan",
                              scan_at(0.1 * static_cast<double>(i), stamps[i])));
  // A message without a stamp: the trajectory falls back to its arrival time.
  ASSERT_TRUE(
      robot.publish(std::string("v2/robot/") + kRobot + "/pose", std::string_view(R"({"x": 1, "y": 0})")));
  ASSERT_TRUE(wait_until([&] { return seen_of(kRobot).size() == stamps.size() + 1; }, 20s))
      << group.log("gateway");
  const std::vector<RobotObservation> seen = seen_of(kRobot);
  for (size_t i = 0; i < stamps.size(); ++i)
    EXPECT_EQ(seen[i].robot_stamp_ns(), static_cast<int64_t>(stamps[i] * 1e9)) << "observation " << i;
  EXPECT_EQ(seen.back().robot_stamp_ns(), 0);

  // The mapper integrates at its next tick: ask until it has all six.
  const std::string tum = group.dir() + "/stamped.tum";
  std::pair<int, std::string> run;
  ASSERT_TRUE(wait_until(
      [&] {
        run = ctl({"trajectory", kRobot, tum});
        return run.first == 0 && run.second.find("wrote 6 poses") != std::string::npos;
      },
      30s, 200ms))
      << run.second << group.log("mapper");
  EXPECT_EQ(std::count(run.second.begin(), run.second.end(), '\n'), 1) << run.second;
  EXPECT_NE(run.second.find("100.000000000 to "), std::string::npos) << run.second;

  const std::vector<std::string> lines = lines_of(tum);
  ASSERT_EQ(lines.size(), 6u);
  const std::vector<std::string> expected{"100.000000000 0.000000 0.000000 0 0 0 0.000000000 1.000000000",
                                          "100.250000000 0.100000 0.000000 0 0 0 0.000000000 1.000000000",
                                          "100.500000000 0.200000 0.000000 0 0 0 0.000000000 1.000000000",
                                          "100.750000000 0.300000 0.000000 0 0 0 0.000000000 1.000000000",
                                          "101.000000000 0.400000 0.000000 0 0 0 0.000000000 1.000000000"};
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(lines[i], expected[i]) << "line " << i;
  const double arrival_s = std::stod(lines.back().substr(0, lines.back().find(' ')));
  EXPECT_GT(arrival_s, 1.6e9) << "the unstamped message's arrival time (Unix epoch): " << lines.back();

  const std::string carmen = group.dir() + "/stamped.log";
  const auto as_carmen = ctl({"trajectory", kRobot, carmen, "--format", "carmen"});
  EXPECT_EQ(as_carmen.first, 0) << as_carmen.second;
  const std::vector<std::string> odom = lines_of(carmen);
  ASSERT_EQ(odom.size(), 6u);
  EXPECT_EQ(odom.front(), "ODOM 0.000000 0.000000 0.000000 0 0 0 100.000000000 slamfleet 100.000000000");

  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"trajectory", "ghost", tum},
        std::vector<std::string>{"trajectory", kRobot, "/nonexistent-dir/stamped.tum"}}) {
    const auto refused = ctl(bad);
    EXPECT_NE(refused.first, 0) << refused.second;
    EXPECT_EQ(std::count(refused.second.begin(), refused.second.end(), '\n'), 1) << refused.second;
  }
  EXPECT_NE(ctl({"trajectory", "ghost", tum}).second.find("UNKNOWN_ROBOT"), std::string::npos);
}

}  // namespace
}  // namespace slam::testkit
