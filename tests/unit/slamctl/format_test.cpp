// slamctl's human-readable lines and JSON.
#include "slamctl/format.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

namespace slam::ctl {
namespace {

TEST(SlamctlFormat, RobotLineShowsPoseAgeAndMode) {
  msg::RobotState s;
  s.robot_id = "r7";
  s.online = true;
  s.protocol_v2 = false;
  s.pose.x = 1.5;
  s.pose.y = -2.25;
  s.last_seen_ns = 1'000'000'000;
  s.messages = 12;
  msg::RobotPath p;
  p.mode = msg::GoalMode::Explore;
  p.status = msg::GoalStatus::Active;
  const std::string line = format_robot(s, nullptr, &p, 3'500'000'000);
  EXPECT_NE(line.find("r7"), std::string::npos);
  EXPECT_NE(line.find("online"), std::string::npos);
  EXPECT_NE(line.find("1.50"), std::string::npos);
  EXPECT_NE(line.find("-2.25"), std::string::npos);
  EXPECT_NE(line.find("2.5 s ago"), std::string::npos);
  EXPECT_NE(line.find("explore/active"), std::string::npos);
  EXPECT_NE(line.find("correction -"), std::string::npos) << line;
}

TEST(SlamctlFormat, RobotLineShowsTheCorrection) {
  msg::RobotState s;
  s.robot_id = "r7";
  msg::PoseCorrection c;
  c.robot_id = "r7";
  c.map_from_odom = {1.0, -2.0, -1.5707963267948966};
  c.version = 4;
  c.keyframes = 31;
  c.loop_closures = 2;
  c.source = msg::CorrectionSource::Loop;
  c.covariance = {0.0004, 0.0, 0.0, 0.0036, 0.0, 0.0001};  // 2 cm along x, 6 cm along y
  const std::string line = format_robot(s, &c, nullptr, 0);
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << line;
  EXPECT_NE(line.find("correction (1.00, -2.00, -90.0 deg) ±6 cm version 4 keyframes 31 loops 2 loop"),
            std::string::npos)
      << line;
}

TEST(SlamctlFormat, ARobotNotYetFoundOnTheMapSaysSoWithItsScore) {
  msg::RobotState s;
  s.robot_id = "r8";
  msg::PoseCorrection c;
  c.robot_id = "r8";
  c.placement = msg::RobotPlacement::Placing;
  c.localisation_score = 0.62;
  const std::string line = format_robot(s, &c, nullptr, 0);
  EXPECT_NE(line.find("correction placing (score 0.62) (0.00, 0.00, 0.0 deg)"), std::string::npos) << line;
  c.placement = msg::RobotPlacement::Placed;
  EXPECT_EQ(format_robot(s, &c, nullptr, 0).find("placing"), std::string::npos);
}

TEST(SlamctlFormat, PathReplyListsStatusAndPoints) {
  msg::PathReply r;
  r.status = msg::PlanStatus::GoalBlocked;
  r.reason = "goal inside an obstacle";
  r.path = {{1, 2}};
  const std::string text = format_path_reply(r);
  EXPECT_NE(text.find("GOAL_BLOCKED"), std::string::npos);
  EXPECT_NE(text.find("goal inside an obstacle"), std::string::npos);
  EXPECT_NE(text.find("(1.00, 2.00)"), std::string::npos);
}

msg::Heartbeat heartbeat(const char* service, double uptime_s,
                         std::vector<std::pair<std::string, int64_t>> counters) {
  msg::Heartbeat hb;
  hb.service = service;
  hb.instance_id = "host:42";
  hb.state = msg::ServiceState::Running;
  hb.uptime_s = uptime_s;
  hb.stamp_ns = 0;
  hb.counters = std::move(counters);
  return hb;
}

TEST(SlamctlFormat, RatesComeFromTwoHeartbeats) {
  const auto first = heartbeat("gateway", 10.0, {{"messages_in", 100}, {"observations", 50}});
  const auto latest = heartbeat("gateway", 12.0, {{"messages_in", 140}, {"observations", 50}, {"new", 3}});
  const ServiceSeen seen = service_seen(first, latest);
  EXPECT_DOUBLE_EQ(seen.rates.at("messages_in"), 20.0);
  EXPECT_DOUBLE_EQ(seen.rates.at("observations"), 0.0);
  EXPECT_FALSE(seen.rates.contains("new")) << "a counter the first heartbeat lacked has no rate";
  EXPECT_TRUE(service_seen(latest, latest).rates.empty()) << "one heartbeat: no rates";
}

TEST(SlamctlFormat, ServiceLineShowsMainRatesAndOnlyNonZeroErrors) {
  const auto first = heartbeat("gateway", 10.0, {{"messages_in", 100}, {"publish_failures", 0}});
  const auto latest =
      heartbeat("gateway", 11.0,
                {{"messages_in", 110}, {"publish_failures", 0}, {"rejected_bad_json", 3}, {"statuses", 9}});
  const std::string line = format_service(service_seen(first, latest), 1'000'000'000, false);
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << line;
  EXPECT_NE(line.find("gateway"), std::string::npos) << line;
  EXPECT_NE(line.find("running"), std::string::npos) << line;
  EXPECT_NE(line.find("up     11.0 s"), std::string::npos) << line;
  EXPECT_NE(line.find("messages_in 10.0/s"), std::string::npos) << line;
  EXPECT_NE(line.find("errors: rejected_bad_json 3"), std::string::npos) << line;
  EXPECT_EQ(line.find("publish_failures"), std::string::npos) << "zero errors are not shown: " << line;
  EXPECT_EQ(line.find("statuses"), std::string::npos) << "not a main counter: " << line;

  const std::string verbose = format_service(service_seen(first, latest), 1'000'000'000, true);
  EXPECT_EQ(std::count(verbose.begin(), verbose.end(), '\n'), 5) << verbose;
  EXPECT_NE(verbose.find("statuses"), std::string::npos) << verbose;
}

TEST(SlamctlFormat, ErrorCountersAreRecognisedByName) {
  for (const char* name : {"write_failures", "robots_refused", "rejected_bad_json", "traffic_dropped",
                           "observation_batches_lost", "request_errors", "loop_overruns"})
    EXPECT_TRUE(is_error_counter(name)) << name;
  for (const char* name : {"messages_in", "robots_online", "waypoints_sent", "alerts_active"})
    EXPECT_FALSE(is_error_counter(name)) << name;
  EXPECT_FALSE(main_counters("planner").empty());
  EXPECT_TRUE(main_counters("unknown-service").empty());
}

TEST(SlamctlFormat, StatusJsonCarriesCountersRatesAndErrors) {
  const auto first = heartbeat("mapper", 1.0, {{"observations", 10}, {"store_errors", 1}});
  const auto latest = heartbeat("mapper", 3.0, {{"observations", 30}, {"store_errors", 1}});
  const auto json = nlohmann::json::parse(services_json({service_seen(first, latest)}, 2'000'000'000));
  ASSERT_TRUE(json.is_array());
  ASSERT_EQ(json.size(), 1u);
  EXPECT_EQ(json[0]["service"], "mapper");
  EXPECT_EQ(json[0]["instance"], "host:42");
  EXPECT_EQ(json[0]["state"], "running");
  EXPECT_DOUBLE_EQ(json[0]["uptime_s"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(json[0]["seen_s_ago"].get<double>(), 2.0);
  EXPECT_EQ(json[0]["counters"]["observations"], 30);
  EXPECT_DOUBLE_EQ(json[0]["rates"]["observations"].get<double>(), 10.0);
  EXPECT_EQ(json[0]["errors"]["store_errors"], 1);
  EXPECT_FALSE(json[0]["errors"].contains("observations"));
}

TEST(SlamctlFormat, RobotsJsonHasNullsForWhatIsUnknown) {
  RobotSeen v1;
  v1.state.robot_id = "legacy";
  v1.state.protocol_v2 = false;
  v1.state.online = false;
  v1.state.battery = -1.0f;
  v1.state.pose.x = 1.5;
  RobotSeen v2;
  v2.state.robot_id = "modern";
  v2.state.protocol_v2 = true;
  v2.state.online = true;
  v2.state.has_heading = true;
  v2.state.pose.theta = 0.5;
  v2.state.battery = 0.75f;
  v2.path = msg::RobotPath{};
  v2.path->mode = msg::GoalMode::Home;
  v2.path->status = msg::GoalStatus::Active;
  v2.correction = msg::PoseCorrection{};
  v2.correction->version = 4;
  v2.correction->covariance = {0.01, 0.0, 0.0, 0.0025, 0.0, 0.0};
  const auto json = nlohmann::json::parse(robots_json({v1, v2}, 0));
  ASSERT_EQ(json.size(), 2u);
  EXPECT_EQ(json[0]["id"], "legacy");
  EXPECT_EQ(json[0]["presence"], "offline");
  EXPECT_EQ(json[1]["presence"], "online");
  EXPECT_EQ(json[1]["protocol"], "v2");
  EXPECT_EQ(json[0]["protocol"], "v1");
  EXPECT_DOUBLE_EQ(json[0]["x"].get<double>(), 1.5);
  EXPECT_TRUE(json[0]["theta"].is_null());
  EXPECT_TRUE(json[0]["battery"].is_null());
  EXPECT_TRUE(json[0]["goal"].is_null());
  EXPECT_TRUE(json[0]["correction"].is_null());
  EXPECT_DOUBLE_EQ(json[1]["theta"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(json[1]["battery"].get<double>(), 0.75);
  EXPECT_EQ(json[1]["goal"]["mode"], "home");
  EXPECT_EQ(json[1]["goal"]["status"], "active");
  EXPECT_EQ(json[1]["correction"]["version"], 4);
  EXPECT_DOUBLE_EQ(json[1]["correction"]["sigma_m"].get<double>(), 0.1);
}

msg::Alert alert(const char* id, msg::AlertKind kind, bool active) {
  return {id,
          kind,
          "sim-1",
          active,
          1'000'000'000,
          2'000'000'000,
          "robot 'sim-1' battery 10 % (below 20 %): sent home",
          "host:7"};
}

TEST(SlamctlFormat, EchoedSamplesNameTheirEnumerations) {
  RobotPath p;
  p.robot_id("r1");
  p.goal_id(3);
  p.mode(GOAL_EXPLORE);
  p.status(GOAL_STATUS_REACHED);
  EXPECT_EQ(describe(p), "path r1 goal 3 explore/reached target (0.00, 0.00) waypoint 0 of 0 ");
  Alert a;
  a.alert_id("offline/r1");
  a.kind(ALERT_ROBOT_OFFLINE);
  a.subject("r1");
  a.active(true);
  EXPECT_NE(describe(a).find("alert offline/r1 ACTIVE  robot offline"), std::string::npos) << describe(a);
  PathReply r;
  r.request_id(5);
  r.status(PLAN_NO_PATH);
  EXPECT_NE(describe(r).find("path reply 5 NO_PATH"), std::string::npos) << describe(r);
}

TEST(SlamctlFormat, FleetDigestAndPointsLinesCountRobotsAndPoints) {
  FleetDigest digest;
  digest.gateway_id("vm:42");
  digest.robots().resize(3);
  digest.robots()[0].presence(PRESENCE_ONLINE);
  digest.robots()[1].presence(PRESENCE_OFFLINE);
  digest.robots()[2].presence(PRESENCE_ONLINE);
  EXPECT_EQ(describe(digest), "digest of gateway vm:42: 3 robots, 2 online");
  FleetPoints points;
  points.gateway_id("vm:42");
  points.robots().resize(2);
  points.robots()[0].points().resize(16);
  points.robots()[1].points().resize(5);
  EXPECT_EQ(describe(points), "points of gateway vm:42: 2 robots, 21 points");
}

TEST(SlamctlFormat, ObservationBatchIsALineThenOneIndentedLinePerObservation) {
  RobotObservationBatch batch;
  batch.gateway_id("vm:42");
  batch.batch_seq(7);
  batch.observations().resize(2);
  batch.observations()[0].robot_id("r1");
  batch.observations()[0].seq(3);
  batch.observations()[0].hits().resize(4);
  batch.observations()[1].robot_id("r2");
  batch.observations()[1].seq(9);
  batch.observations()[1].robot_stamp_ns(12'500'000'000);
  EXPECT_EQ(describe(batch),
            "observations of gateway vm:42 batch 7: 2\n"
            "  observation r1 seq 3 pose (0.00, 0.00, -) hits 4 misses 0\n"
            "  observation r2 seq 9 pose (0.00, 0.00, -) hits 0 misses 0 robot stamp 12.500000 s");
}

TEST(SlamctlFormat, AlertLineAndJson) {
  const std::string line =
      format_alert(alert("battery/sim-1", msg::AlertKind::BatteryLow, true), 4'000'000'000);
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << line;
  for (const char* part : {"ACTIVE", "battery low", "sim-1", "raised    3.0 s ago", "host:7", "sent home"})
    EXPECT_NE(line.find(part), std::string::npos) << part << " in " << line;
  EXPECT_NE(format_alert(alert("offline/sim-1", msg::AlertKind::RobotOffline, false), 0).find("cleared"),
            std::string::npos);

  const auto json =
      nlohmann::json::parse(alerts_json({alert("battery/sim-1", msg::AlertKind::BatteryLow, true),
                                         alert("silent/x", msg::AlertKind::ServiceSilent, false)},
                                        4'000'000'000));
  ASSERT_EQ(json.size(), 2u);
  EXPECT_EQ(json[0]["id"], "battery/sim-1");
  EXPECT_EQ(json[0]["kind"], "battery low");
  EXPECT_EQ(json[0]["active"], true);
  EXPECT_DOUBLE_EQ(json[0]["raised_s_ago"].get<double>(), 3.0);
  EXPECT_EQ(json[1]["kind"], "service silent");
  EXPECT_EQ(json[1]["active"], false);
}

}  // namespace
}  // namespace slam::ctl
