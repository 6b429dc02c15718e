// Two slam-gateways and two slam-planners at once, behind one mosquitto, with robots publishing at
// 10 Hz: the test plays the mapper (GridSnapshot) and the operator (NavGoal), the robots are
// `mosquitto_pub` pipelines and one MQTT client that receives their waypoints. Each robot's
// waypoint commands come from one planner per period (the DDS writer is counted), every command
// reaches its robot over MQTT exactly once (planner command ids are unique), and after `kill -9` of
// one gateway and one planner under load every robot is served again by the survivors, with the
// same guarantees after. The takeover time is measured and printed, not asserted
// (docs/deployment.md holds the figures).
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "process_group.hpp"
#include "robot_publishers.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;
using testkit::bin_path;
using testkit::wait_until;
using Clock = std::chrono::steady_clock;

constexpr int kRobots = 16;
constexpr auto kPeriod = 1s;  // a robot's commands within one period must come from one planner

std::string robot_id(int i) {
  return "scale-" + std::to_string(i);
}
// Robot i stands in its own lane, 1 m apart, and is sent along it: the robots never meet.
double lane_y(int i) {
  return 1.0 + i;
}

struct Command {  // a WaypointCommand as seen on DDS
  std::string robot;
  uint64_t seq;
  std::string writer;  // the planner's writer GUID
  Clock::time_point at;
};

class ScaledServicesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const int port = group.start_mosquitto();
    const std::string domain_arg = std::to_string(domain.id());
    for (const char* name : {"gw-a", "gw-b"}) {
      group.start(name, {bin_path("slam-gateway"), "--domain", domain_arg, "--broker",
                         "tcp://127.0.0.1:" + std::to_string(port)});
    }
    for (const char* name : {"planner-a", "planner-b"}) {
      group.start(name, {bin_path("slam-planner"), "--domain", domain_arg, "--goals-resend-period-s", "0.2",
                         "--goal-store", group.dir() + "/goals-" + name + ".json"});
    }
    participant = std::move(*dds::Participant::create(domain.id(), "scaled-services-test"));
    snapshots = testkit::make_test_writer(*participant, dds::kGridSnapshot);
    goals = testkit::make_test_writer(*participant, dds::kNavGoal);
    command_reader = std::move(*dds::make_reader(
        *participant, dds::kWaypointCommand,
        [this](const WaypointCommand& c, const dds::fdds::SampleInfo& info) {
          std::ostringstream writer;
          writer << info.sample_identity.writer_guid();
          std::lock_guard lock(mutex);
          commands.push_back({c.robot_id().to_string(), c.seq(), writer.str(), Clock::now()});
        }));
    heartbeat_reader =
        std::move(*dds::make_reader(*participant, dds::kHeartbeat, [this](const Heartbeat& h, const auto&) {
          std::lock_guard lock(mutex);
          auto& values = service_counters[h.service().to_string()][h.instance_id().to_string()];
          for (const auto& c : h.counters()) values[c.name().to_string()] = c.value();
        }));
    robots = std::make_unique<testkit::MqttTestClient>(port, "scale-robots");
    ASSERT_EQ(robots->connect(), 0);
    ASSERT_TRUE(robots->subscribe("v2/server/+/waypoint"));
    std::vector<std::string> topics;
    for (int i = 0; i < kRobots; ++i) topics.push_back("v2/robot/" + robot_id(i) + "/pose");
    publishers = std::make_unique<testkit::RobotPublishers>(port, topics, "scale-pub");
    ASSERT_TRUE(publishers->ok());
    ASSERT_TRUE(goals->wait_for_readers(60s, 2)) << logs();
    ASSERT_TRUE(snapshots->wait_for_readers(60s, 2)) << logs();
  }

  void TearDown() override {
    stop_load();
    if (HasFailure()) std::cerr << logs();
  }

  std::string logs() const {
    return group.log("gw-a") + group.log("gw-b") + group.log("planner-a") + group.log("planner-b");
  }

  // The robots publish their poses at 10 Hz until stop_load().
  void start_load() {
    load = std::thread([this] {
      while (loading) {
        for (int i = 0; i < kRobots; ++i) {
          char line[96];
          std::snprintf(line, sizeof line, "{\"x\": 1.0, \"y\": %.1f, \"heading\": 0.0}", lane_y(i));
          publishers->publish(static_cast<size_t>(i), line);
        }
        std::this_thread::sleep_for(100ms);
      }
    });
  }
  void stop_load() {
    loading = false;
    if (load.joinable()) load.join();
  }

  // The mapper's side: a 20 x 20 m grid, all free. The operator's: each robot sent along its lane.
  void publish_world_and_goals() {
    GridSnapshot s;
    s.layout_id(1);
    s.version(1);
    s.info().width(200);
    s.info().height(200);
    s.info().resolution(0.1);
    s.cells(std::vector<uint8_t>(200 * 200, 1));
    ASSERT_TRUE(snapshots->write(s));
    for (int i = 0; i < kRobots; ++i) {
      NavGoal g;
      g.robot_id(robot_id(i));
      g.goal_id(500 + static_cast<uint64_t>(i));
      g.mode(GOAL_DIRECT);
      g.target().x(15.0);
      g.target().y(lane_y(i));
      ASSERT_TRUE(goals->write(g));
    }
  }

  // Counter `name` of every instance of `service` heard.
  std::vector<int64_t> counters(const std::string& service, const std::string& name) {
    std::lock_guard lock(mutex);
    std::vector<int64_t> out;
    for (const auto& [instance, values] : service_counters[service]) {
      const auto it = values.find(name);
      out.push_back(it == values.end() ? -1 : it->second);
    }
    return out;
  }
  int64_t counter_sum(const std::string& service, const std::string& name) {
    int64_t sum = 0;
    for (int64_t v : counters(service, name)) sum += std::max<int64_t>(v, 0);
    return sum;
  }

  std::vector<Command> commands_between(Clock::time_point from, Clock::time_point to) {
    std::lock_guard lock(mutex);
    std::vector<Command> out;
    for (const Command& c : commands)
      if (c.at >= from && c.at < to) out.push_back(c);
    return out;
  }

  // MQTT waypoints received: (robot, seq) -> copies and when the first arrived.
  struct Delivery {
    int copies = 0;
    Clock::time_point first;
  };
  std::map<std::pair<std::string, uint64_t>, Delivery> deliveries() {
    std::map<std::pair<std::string, uint64_t>, Delivery> out;
    for (const auto& m : robots->messages()) {
      const std::string robot = m.topic.substr(10, m.topic.size() - 10 - 9);  // v2/server/<id>/waypoint
      Delivery& d = out[{robot, nlohmann::json::parse(m.payload)["seq"].get<uint64_t>()}];
      if (d.copies++ == 0) d.first = m.received_at;
    }
    return out;
  }

  // In [from, to): every robot was commanded, each robot by one planner per period, and every
  // command reached its robot exactly once.
  void expect_steady(Clock::time_point from, Clock::time_point to, const char* phase) {
    SCOPED_TRACE(phase);
    const std::vector<Command> window = commands_between(from, to);
    std::map<std::pair<std::string, int64_t>, std::set<std::string>> writers;  // (robot, period)
    std::set<std::string> commanded;
    for (const Command& c : window) {
      writers[{c.robot, (c.at - from) / kPeriod}].insert(c.writer);
      commanded.insert(c.robot);
    }
    EXPECT_EQ(commanded.size(), static_cast<size_t>(kRobots)) << "robots without commands";
    for (const auto& [key, set] : writers)
      EXPECT_EQ(set.size(), 1u) << key.first << " commanded by " << set.size() << " planners in period "
                                << key.second;
    // Let the last commands arrive over MQTT before counting them.
    ASSERT_TRUE(wait_until(
        [&] {
          const auto got = deliveries();
          return std::all_of(window.begin(), window.end(), [&](const Command& c) {
            return got.count({c.robot, c.seq}) > 0;
          });
        },
        10s))
        << "commands that never reached their robot";
    const auto got = deliveries();
    for (const Command& c : window)
      EXPECT_EQ(got.at({c.robot, c.seq}).copies, 1) << c.robot << " seq " << c.seq;
  }

  testkit::DomainLease domain;
  testkit::ProcessGroup group;
  std::mutex mutex;
  std::vector<Command> commands;
  std::map<std::string, std::map<std::string, std::map<std::string, int64_t>>> service_counters;
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Writer<GridSnapshot>> snapshots;
  std::unique_ptr<dds::Writer<NavGoal>> goals;
  std::unique_ptr<dds::Reader<WaypointCommand>> command_reader;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader;
  std::unique_ptr<testkit::MqttTestClient> robots;  // receives the waypoints
  std::unique_ptr<testkit::RobotPublishers> publishers;
  std::atomic<bool> loading{true};
  std::thread load;
};

TEST_F(ScaledServicesTest, TwoGatewaysAndTwoPlannersServeEachRobotOnceAndSurviveAKillOfOneOfEach) {
  start_load();
  ASSERT_NO_FATAL_FAILURE(publish_world_and_goals());
  // Everyone warmed up and hearing their peer; the robots shared out among both of each.
  ASSERT_TRUE(wait_until(
      [&] {
        const auto gw = counters("gateway", "robots_owned");
        const auto pl = counters("planner", "robots_owned");
        return gw.size() == 2 && pl.size() == 2 && std::ranges::all_of(gw, [](int64_t n) { return n > 0; }) &&
               std::ranges::all_of(pl, [](int64_t n) { return n > 0; }) &&
               counter_sum("gateway", "robots_owned") == kRobots &&
               counter_sum("planner", "robots_owned") == kRobots;
      },
      40s))
      << "gateways own " << counter_sum("gateway", "robots_owned") << ", planners own "
      << counter_sum("planner", "robots_owned") << " of " << kRobots;
  std::this_thread::sleep_for(1s);  // commands sent before the shares settled are not judged
  const auto steady_from = Clock::now();
  std::this_thread::sleep_for(3s);
  ASSERT_NO_FATAL_FAILURE(expect_steady(steady_from, Clock::now(), "both of each"));

  // kill -9 one gateway and one planner at once, under load.
  group.stop("gw-a", SIGKILL);
  group.stop("planner-a", SIGKILL);
  const auto killed_at = Clock::now();
  // Takeover: every robot has received a waypoint the surviving planner commanded after the kill
  // (the killed planner sends nothing after it; 100 ms covers what it had in flight).
  std::map<std::string, double> served_after_s;
  ASSERT_TRUE(wait_until(
      [&] {
        const auto got = deliveries();
        for (const Command& c : commands_between(killed_at + 100ms, Clock::now())) {
          const auto it = got.find({c.robot, c.seq});
          if (it != got.end() && !served_after_s.contains(c.robot))
            served_after_s[c.robot] = std::chrono::duration<double>(it->second.first - killed_at).count();
        }
        return served_after_s.size() == static_cast<size_t>(kRobots);
      },
      20s))
      << served_after_s.size() << " of " << kRobots << " robots served again after the kill";
  double takeover_s = 0.0;
  for (const auto& [robot, s] : served_after_s) takeover_s = std::max(takeover_s, s);

  // The survivors own every robot (counters heard from now on: the killed ones beat no more) and
  // serve each exactly once.
  {
    std::lock_guard lock(mutex);
    service_counters.clear();
  }
  ASSERT_TRUE(wait_until(
      [&] {
        return counters("gateway", "robots_owned") == std::vector<int64_t>{kRobots} &&
               counters("planner", "robots_owned") == std::vector<int64_t>{kRobots};
      },
      10s));
  const auto after_from = Clock::now();
  std::this_thread::sleep_for(3s);
  ASSERT_NO_FATAL_FAILURE(expect_steady(after_from, Clock::now(), "survivors"));
  stop_load();

  // No waypoint reached a robot twice, before, during or after the kill.
  for (const auto& [key, delivery] : deliveries())
    EXPECT_EQ(delivery.copies, 1) << key.first << " waypoint seq " << key.second;
  std::printf(
      "[ figures ] takeover after kill -9 of a gateway and a planner: %.2f s (all %d robots served again)\n",
      takeover_s, kRobots);
  RecordProperty("takeover_s", std::to_string(takeover_s));
}

}  // namespace
}  // namespace slam
