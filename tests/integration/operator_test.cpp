// Operator tools over DDS against real processes (mosquitto, gateway, planner and a v2 robot spoken
// by the test over MQTT): a robot gone offline, a low battery (alert, and the robot sent home) and a
// service killed without a word raise alerts that `slamctl alerts` lists; `slamctl forget` makes the
// gateway and the planner drop a robot.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

struct CtlRun {
  int code = -1;
  std::string output;
};

class OperatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto p = dds::Participant::create(domain.id(), "operator-test");
    if (!p) throw std::runtime_error(p.message());
    participant = std::move(*p);
    alert_reader = make_inbox_reader(*participant, dds::kAlert, alerts);
    path_reader = make_inbox_reader(*participant, dds::kRobotPath, paths);
    heartbeat_reader = make_inbox_reader(*participant, dds::kHeartbeat, heartbeats);
    goal_writer = make_test_writer(*participant, dds::kNavGoal);

    const std::string d = std::to_string(domain.id());
    group.start("gateway", {bin_path("slam-gateway"), "--domain", d, "--broker",
                            "tcp://127.0.0.1:" + std::to_string(port), "--no-share"});
    group.start("planner", {bin_path("slam-planner"), "--domain", d, "--no-share", "--goal-store", goal_file,
                            "--alerts-battery-low", "0.3", "--alerts-service-silent-s", "2"});
    ASSERT_EQ(robot.connect(), 0);
  }
  void TearDown() override {
    if (!HasFailure()) return;
    for (const char* s : {"gateway", "planner"}) std::cerr << s << " log:\n" << group.log(s) << "\n";
  }

  CtlRun ctl(std::vector<std::string> args) {
    const std::string name = "slamctl" + std::to_string(++runs);
    std::vector<std::string> argv{bin_path("slamctl"), "--domain", std::to_string(domain.id()), "--timeout",
                                  "10"};
    argv.insert(argv.end(), args.begin(), args.end());
    group.start(name, argv);
    CtlRun r;
    r.code = group.wait_exit(name, 60s);
    r.output = group.log(name);
    return r;
  }
  bool alert_is(const std::string& id, bool active) {
    const auto latest = alerts.last([&](const Alert& a) { return a.alert_id().to_string() == id; });
    return latest && latest->active() == active;
  }
  // The latest heartbeat counter `name` of `service`; -1 before any.
  int64_t counter(const std::string& service, const std::string& name) {
    const auto hb = heartbeats.last([&](const Heartbeat& h) { return h.service().to_string() == service; });
    if (!hb) return -1;
    for (const auto& c : hb->counters())
      if (c.name().to_string() == name) return c.value();
    return -1;
  }
  void report_pose(double x, double y) {
    ASSERT_TRUE(robot.publish("v2/robot/r1/pose", R"({"x": )" + std::to_string(x) + R"(, "y": )" +
                                                      std::to_string(y) + R"(, "heading": 0.0})"));
  }
  // Reports the pose until the gateway has turned a report into a RobotState: the gateway subscribes
  // to the broker a moment after it starts, and the broker drops a report sent before that.
  void report_first_pose(double x, double y) {
    ASSERT_TRUE(wait_until(
        [&] {
          report_pose(x, y);
          return counter("gateway", "robot_states") > 0;
        },
        20s, 100ms))
        << group.log("gateway");
  }

  DomainLease domain;
  ProcessGroup group;
  int port = group.start_mosquitto();
  std::string goal_file = group.dir() + "/goals.json";
  MqttTestClient robot{port, "r1"};
  Inbox<Alert> alerts;
  Inbox<RobotPath> paths;
  Inbox<Heartbeat> heartbeats;
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Reader<Alert>> alert_reader;
  std::unique_ptr<dds::Reader<RobotPath>> path_reader;
  std::unique_ptr<dds::Reader<Heartbeat>> heartbeat_reader;
  std::unique_ptr<dds::Writer<NavGoal>> goal_writer;
  int runs = 0;
};

TEST_F(OperatorTest, LowBatteryOfflineAndSilentServiceRaiseAlerts) {
  report_first_pose(1.0, 2.0);
  ASSERT_TRUE(robot.publish("v2/robot/r1/status", R"({"battery": 0.9, "state": "exploring"})"));
  ASSERT_TRUE(wait_until([&] { return counter("planner", "robots_sent_home") == 0; }, 20s));

  // Low battery: the planner that owns the robot raises the alert and sends it home.
  ASSERT_TRUE(robot.publish("v2/robot/r1/status", R"({"battery": 0.1, "state": "exploring"})"));
  ASSERT_TRUE(wait_until([&] { return alert_is("battery/r1", true); }, 20s)) << group.log("planner");
  EXPECT_TRUE(wait_until(
      [&] {
        return paths.last([](const RobotPath& p) { return p.robot_id() == "r1" && p.mode() == GOAL_HOME; })
            .has_value();
      },
      20s))
      << "the robot was not sent home:\n"
      << group.log("planner");
  EXPECT_TRUE(wait_until([&] { return counter("planner", "robots_sent_home") == 1; }, 10s));

  // Offline (its last will), and a service killed without saying it stops.
  ASSERT_TRUE(robot.publish("v2/robot/r1/status", R"({"state": "offline"})"));
  ASSERT_TRUE(wait_until([&] { return alert_is("offline/r1", true); }, 20s)) << group.log("planner");
  group.start("mapper", {bin_path("slam-mapper"), "--domain", std::to_string(domain.id()), "--store",
                         group.dir() + "/map.db"});
  ASSERT_TRUE(wait_until([&] { return counter("mapper", "observations") >= 0; }, 20s)) << group.log("mapper");
  group.stop("mapper", 9);
  const auto silent =
      alerts.wait_for([](const Alert& a) { return a.kind() == ALERT_SERVICE_SILENT && a.active(); }, 20s);
  ASSERT_TRUE(silent) << group.log("planner");
  EXPECT_EQ(silent->alert_id().to_string().rfind("silent/mapper/", 0), 0u) << silent->alert_id();

  // slamctl lists the active ones, as text and as JSON.
  const CtlRun text = ctl({"alerts"});
  EXPECT_EQ(text.code, 0) << text.output;
  for (const char* part : {"battery low", "robot offline", "service silent", "r1"})
    EXPECT_NE(text.output.find(part), std::string::npos) << part << " in:\n" << text.output;
  const CtlRun json = ctl({"alerts", "--json"});
  ASSERT_EQ(json.code, 0) << json.output;
  const auto listed = nlohmann::json::parse(json.output);
  std::vector<std::string> ids;
  for (const auto& a : listed) ids.push_back(a["id"]);
  EXPECT_NE(std::find(ids.begin(), ids.end(), "battery/r1"), ids.end()) << json.output;
  EXPECT_NE(std::find(ids.begin(), ids.end(), "offline/r1"), ids.end()) << json.output;

  // Back online with a full battery: both robot alerts clear.
  report_pose(1.0, 2.0);
  ASSERT_TRUE(robot.publish("v2/robot/r1/status", R"({"battery": 0.95, "state": "charging"})"));
  EXPECT_TRUE(wait_until([&] { return alert_is("offline/r1", false) && alert_is("battery/r1", false); }, 20s))
      << group.log("planner");
  const CtlRun cleared = ctl({"alerts"});
  EXPECT_EQ(cleared.code, 0) << cleared.output;
  EXPECT_EQ(cleared.output.find("battery low"), std::string::npos) << cleared.output;
  EXPECT_NE(ctl({"alerts", "--all"}).output.find("cleared"), std::string::npos);
}

TEST_F(OperatorTest, ForgetMakesGatewayAndPlannerDropTheRobot) {
  report_first_pose(1.0, 2.0);
  NavGoal goal;
  goal.robot_id("r1");
  goal.goal_id(77);
  goal.mode(GOAL_DIRECT);
  goal.target().x(3.0);
  goal.target().y(2.0);
  ASSERT_TRUE(goal_writer->wait_for_readers(20s));
  ASSERT_TRUE(goal_writer->write(goal));
  ASSERT_TRUE(wait_until(
      [&] { return paths.last([](const RobotPath& p) { return p.goal_id() == 77; }).has_value(); }, 20s))
      << group.log("planner");
  ASSERT_TRUE(wait_until([&] { return ctl({"robots"}).output.find("r1") != std::string::npos; }, 20s));

  const CtlRun forget = ctl({"forget", "r1"});
  ASSERT_EQ(forget.code, 0) << forget.output;
  EXPECT_NE(forget.output.find("robot r1 forgotten"), std::string::npos) << forget.output;
  EXPECT_TRUE(wait_until(
      [&] {
        return counter("gateway", "robots_forgotten") == 1 && counter("planner", "robots_forgotten") == 1;
      },
      20s));

  // Late joiners get neither its state (the gateway disposed it) nor its path (the planner did).
  const CtlRun robots = ctl({"robots"});
  EXPECT_NE(robots.code, 0) << robots.output;
  Inbox<RobotPath> late_paths;
  auto late = make_inbox_reader(*participant, dds::kRobotPath, late_paths);
  ASSERT_TRUE(late->wait_for_writers(20s));
  std::this_thread::sleep_for(1s);  // what the planner keeps for late joiners arrives right after the match
  EXPECT_FALSE(late_paths.last([](const RobotPath& p) { return p.robot_id() == "r1"; }));
  // The planner's goal file no longer holds its goal or its home.
  std::ifstream file(goal_file);
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_EQ(text.str().find("\"r1\""), std::string::npos) << text.str();

  // When it reports again it is a new robot: counters start afresh, no goal is resumed.
  report_pose(1.5, 2.0);
  CtlRun again;
  ASSERT_TRUE(wait_until(
      [&] {
        again = ctl({"robots", "--json"});
        return again.code == 0;
      },
      20s));
  const auto listed = nlohmann::json::parse(again.output);
  ASSERT_EQ(listed.size(), 1u) << again.output;
  EXPECT_EQ(listed[0]["id"], "r1");
  EXPECT_EQ(listed[0]["messages"], 1) << again.output;
  EXPECT_TRUE(listed[0]["goal"].is_null() || listed[0]["goal"]["goal_id"] != 77) << again.output;
}

}  // namespace
}  // namespace slam::testkit
