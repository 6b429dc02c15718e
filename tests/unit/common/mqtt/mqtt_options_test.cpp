// ConnectionOptions: the defaults are valid and each bad setting is named.
#include "common/mqtt/mqtt_options.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace slam::mqtt {
namespace {

std::string error_with(const std::function<void(ConnectionOptions&)>& change) {
  ConnectionOptions o;
  change(o);
  const Status s = validate(o);
  return s ? std::string() : s.message();
}

TEST(MqttConnectionOptions, DefaultsAreValid) {
  EXPECT_TRUE(validate(ConnectionOptions{}));
  EXPECT_EQ(error_with([](auto& o) { o.client_id = "robot-1"; }), "");
}

TEST(MqttConnectionOptions, NamesTheBadSetting) {
  EXPECT_NE(error_with([](auto& o) { o.broker = "http://x"; }).find("broker"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.broker = "tcp://"; }).find("broker"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.qos = 3; }).find("qos"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.persistent_session = true; }).find("client-id"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.password = "secret"; }).find("username"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.keepalive_s = 0; }).find("keepalive-s"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.connect_timeout_s = 0; }).find("connect-timeout-s"),
            std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.reconnect_min_s = 0.0; }).find("reconnect-min-s"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.reconnect_max_s = 0.1; }).find("reconnect-max-s"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.subscriptions.emplace_back(); }).find("subscribe"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.will = Will{"", "offline"}; }).find("will"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) { o.max_buffered_messages = 0; }).find("max-buffered-messages"),
            std::string::npos);
}

TEST(MqttConnectionOptions, TlsFilesNeedATlsBrokerAndReadableFiles) {
  EXPECT_NE(error_with([](auto& o) { o.tls_ca_file = "/etc/hostname"; }).find("ssl://"), std::string::npos);
  EXPECT_NE(error_with([](auto& o) {
              o.broker = "ssl://h:8883";
              o.tls_ca_file = "/nonexistent/ca.pem";
            }).find("tls-ca-file"),
            std::string::npos);
  EXPECT_NE(error_with([](auto& o) {
              o.broker = "ssl://h:8883";
              o.tls_key_file = "/etc/hostname";
            }).find("tls-cert-file"),
            std::string::npos);
  EXPECT_EQ(error_with([](auto& o) { o.broker = "mqtts://h:8883"; }), "");
}

TEST(MqttConnectionOptions, RecognisesTlsBrokers) {
  EXPECT_TRUE(uses_tls("ssl://h:8883"));
  EXPECT_TRUE(uses_tls("mqtts://h:8883"));
  EXPECT_FALSE(uses_tls("tcp://h:1883"));
  EXPECT_FALSE(uses_tls("mqtt://h:1883"));
}

TEST(MqttSharedSubscription, PrefixesTheFilterWithTheGroup) {
  EXPECT_EQ(shared_filter("slam-gateways", "v2/robot/+/+"), "$share/slam-gateways/v2/robot/+/+");
}

TEST(MqttSharedSubscription, RefusesAGroupThatIsNotOneLevel) {
  EXPECT_TRUE(validate_share_group("slam-gateways"));
  EXPECT_FALSE(validate_share_group(""));
  EXPECT_FALSE(validate_share_group("a/b"));
  EXPECT_FALSE(validate_share_group("a+"));
  EXPECT_FALSE(validate_share_group("#"));
}

}  // namespace
}  // namespace slam::mqtt
