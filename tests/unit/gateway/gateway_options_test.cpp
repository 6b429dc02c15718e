// GatewayOptions: defaults are valid, flags bind, each bad value names its key; topic filters.
#include "gateway/core/gateway_options.hpp"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "gateway/core/topic_filter.hpp"

namespace slam::gateway {
namespace {

std::string error_of(const GatewayOptions& o) {
  const Status s = validate(o);
  return s ? std::string() : s.message();
}

TEST(GatewayOptions, DefaultsAreValidAndSubscribeBothTrees) {
  GatewayOptions o;
  EXPECT_EQ(error_of(o), "");
  EXPECT_EQ(o.mqtt.broker, "tcp://127.0.0.1:1883");
  EXPECT_EQ(o.mqtt.subscriptions, (std::vector<std::string>{"v1/robot/+/adv", "v2/robot/+/+"}));
}

TEST(GatewayOptions, FlagsBind) {
  CLI::App app;
  GatewayOptions o;
  add_gateway_options(app, o);
  std::vector<std::string> args{"slam-gateway",
                                "--broker",
                                "mqtt://broker:1884",
                                "--qos",
                                "0",
                                "--client-id",
                                "gw",
                                "--persistent-session",
                                "--subscribe",
                                "a/+",
                                "--subscribe",
                                "b/#",
                                "--units-per-meter",
                                "1000",
                                "--offline-after-s",
                                "2",
                                "--digest-period-s",
                                "0.5",
                                "--digest-points-period-s",
                                "2",
                                "--digest-points-per-robot",
                                "40",
                                "--batch-ms",
                                "2.5"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  app.parse(static_cast<int>(argv.size()), argv.data());
  EXPECT_EQ(o.mqtt.broker, "mqtt://broker:1884");
  EXPECT_EQ(o.mqtt.qos, 0);
  EXPECT_TRUE(o.mqtt.persistent_session);
  EXPECT_EQ(o.mqtt.subscriptions, (std::vector<std::string>{"a/+", "b/#"}));
  EXPECT_DOUBLE_EQ(o.limits.units_per_meter, 1000.0);
  EXPECT_DOUBLE_EQ(o.offline_after_s, 2.0);
  EXPECT_DOUBLE_EQ(o.digest_period_s, 0.5);
  EXPECT_DOUBLE_EQ(o.digest_points_period_s, 2.0);
  EXPECT_EQ(o.digest_points_per_robot, 40u);
  EXPECT_DOUBLE_EQ(o.batch_ms, 2.5);
  EXPECT_EQ(error_of(o), "");
}

TEST(GatewayOptions, BadValuesNameTheKey) {
  auto with = [](auto change) {
    GatewayOptions o;
    change(o);
    return error_of(o);
  };
  EXPECT_NE(with([](auto& o) { o.mqtt.broker = "http://x"; }).find("broker"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.mqtt.broker = "tcp://"; }).find("broker"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.mqtt.qos = 3; }).find("qos"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.mqtt.persistent_session = true; }).find("client-id"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.mqtt.password = "x"; }).find("username"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.mqtt.tls_ca_file = "/etc/hostname"; }).find("ssl://"), std::string::npos);
  EXPECT_NE(with([](auto& o) {
              o.mqtt.broker = "ssl://h:8883";
              o.mqtt.tls_ca_file = "/nonexistent/ca.pem";
            }).find("tls-ca-file"),
            std::string::npos);
  EXPECT_NE(with([](auto& o) {
              o.mqtt.broker = "ssl://h:8883";
              o.mqtt.tls_key_file = "/etc/hostname";
            }).find("tls-cert-file"),
            std::string::npos);
  EXPECT_NE(with([](auto& o) { o.mqtt.reconnect_max_s = 0.01; }).find("reconnect-max-s"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.mqtt.subscriptions = {"a/#/b"}; }).find("subscribe"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.limits.units_per_meter = 0; }).find("units_per_meter"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.offline_after_s = -1; }).find("offline-after-s"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.max_robots = 0; }).find("max-robots"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.batch_ms = -1; }).find("batch-ms"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.traffic_queue = 0; }).find("traffic-queue"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.digest_period_s = 0; }).find("digest-period-s"), std::string::npos);
  EXPECT_NE(with([](auto& o) { o.digest_points_period_s = 100; }).find("digest-points-period-s"),
            std::string::npos);
  EXPECT_NE(with([](auto& o) { o.digest_points_per_robot = 20'000; }).find("digest-points-per-robot"),
            std::string::npos);
}

GatewayOptions parsed(std::vector<std::string> args) {
  CLI::App app;
  GatewayOptions o;
  add_gateway_options(app, o);
  args.insert(args.begin(), "slam-gateway");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  app.parse(static_cast<int>(argv.size()), argv.data());
  return o;
}

TEST(GatewayOptions, SharesTheRobotTopicsByDefault) {
  const GatewayOptions o;
  EXPECT_TRUE(o.share);
  EXPECT_EQ(
      subscribed_filters(o),
      (std::vector<std::string>{
          "$share/slam-gateways/v1/robot/+/adv", "$share/slam-gateways/v2/robot/+/+",
          "$share/slam-gateways/uagv/v2/+/+/connection", "$share/slam-gateways/uagv/v2/+/+/state",
          "$share/slam-gateways/uagv/v2/+/+/visualization", "$share/slam-gateways/uagv/v2/+/+/factsheet"}));
  const auto grouped = parsed({"--share-group", "east", "--peer-timeout-s", "2.5"});
  EXPECT_EQ(subscribed_filters(grouped).front(), "$share/east/v1/robot/+/adv");
  EXPECT_DOUBLE_EQ(grouped.peer_timeout_s, 2.5);
}

TEST(GatewayOptions, NoShareSubscribesThePlainFilters) {
  const auto o = parsed({"--no-share"});
  EXPECT_FALSE(o.share);
  EXPECT_EQ(subscribed_filters(o).front(), o.mqtt.subscriptions.front());
  EXPECT_EQ(subscribed_filters(o).back(), "uagv/v2/+/+/factsheet");
}

TEST(GatewayOptions, Vda5050TreeAndRobotsAreConfigurable) {
  const auto o = parsed({"--no-share", "--vda-interface", "agv", "--vda-major-version", "v3", "--vda-robot",
                         "Acme/agv-1", "--vda-robot", "Acme/agv-2"});
  EXPECT_TRUE(validate(o));
  EXPECT_EQ(o.vda_robots, (std::vector<std::string>{"Acme/agv-1", "Acme/agv-2"}));
  EXPECT_EQ(subscribed_filters(o).back(), "agv/v3/+/+/factsheet");
  const auto off = parsed({"--no-share", "--vda5050", "off"});
  EXPECT_EQ(subscribed_filters(off), off.mqtt.subscriptions);

  for (const auto& [flag, value, key] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"--vda-interface", "a/b", "vda-interface"},
           {"--vda-major-version", "2", "vda-major-version"},
           {"--vda-major-version", "vx", "vda-major-version"},
           {"--vda-robot", "agv-1", "vda-robot"},
           {"--vda-robot", "Acme/+", "vda-robot serialNumber"}}) {
    const Status s = validate(parsed({flag, value}));
    ASSERT_FALSE(s) << flag << " " << value;
    EXPECT_NE(s.message().find(key), std::string::npos) << s.message();
  }
}

TEST(GatewayOptions, BadSharingValuesNameTheKey) {
  GatewayOptions o;
  o.share_group = "a/b";
  EXPECT_NE(error_of(o).find("share-group"), std::string::npos);
  o.share = false;  // not used without sharing
  EXPECT_EQ(error_of(o), "");
  GatewayOptions hasty;
  hasty.peer_timeout_s = 0.5;  // a single heartbeat period
  EXPECT_NE(error_of(hasty).find("peer-timeout-s"), std::string::npos);
}

TEST(TopicFilter, WildcardsOnlyAsWholeLevelsAndHashLast) {
  EXPECT_TRUE(validate_filter("v1/robot/+/adv"));
  EXPECT_TRUE(validate_filter("v2/robot/+/+"));
  EXPECT_TRUE(validate_filter("#"));
  EXPECT_TRUE(validate_filter("a/#"));
  EXPECT_TRUE(validate_filter("/leading/empty//levels"));
  EXPECT_FALSE(validate_filter(""));
  EXPECT_FALSE(validate_filter("a/b+"));
  EXPECT_FALSE(validate_filter("a/#/b"));
  EXPECT_FALSE(validate_filter("a/##"));
  EXPECT_FALSE(validate_filter(std::string(257, 'a')));
  EXPECT_FALSE(validate_filter(std::string("a\x01", 2)));
  EXPECT_FALSE(validate_filter(std::string("a\xff", 2)));
}

TEST(TopicFilter, PublishTopicsHaveNoWildcards) {
  EXPECT_TRUE(validate_topic_name("v1/server/r1/cmd"));
  EXPECT_FALSE(validate_topic_name("v1/server/+/cmd"));
  EXPECT_FALSE(validate_topic_name("a/#"));
  EXPECT_FALSE(validate_topic_name(""));
}

}  // namespace
}  // namespace slam::gateway
