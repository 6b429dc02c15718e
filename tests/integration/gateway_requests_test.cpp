// slam-gateway executing operator MQTT requests from DDS (MqttRequest) against a real mosquitto:
// publish reaches a subscribed client byte for byte, subscribe brings broker traffic onto the
// MqttTraffic topic and unsubscribe stops it, bad topics and filters are refused; every request
// is answered with an MqttReply carrying its id.
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

// The viewer's side of the gateway: requests out, replies and traffic in.
class Operator {
 public:
  explicit Operator(int domain) {
    auto p = dds::Participant::create(domain, "gateway-requests-test");
    if (!p) throw std::runtime_error(p.message());
    participant_ = std::move(*p);
    requests_ = make_test_writer(*participant_, dds::kMqttRequest);
    reply_reader_ = make_inbox_reader(*participant_, dds::kMqttReply, replies_);
    traffic_reader_ = make_inbox_reader(*participant_, dds::kMqttTraffic, traffic_);
    subscriptions_reader_ = make_inbox_reader(*participant_, dds::kMqttSubscriptions, subscriptions_);
  }

  bool ready() const {
    const auto latest = subscriptions_.last([](const MqttSubscriptions&) { return true; });
    return latest && latest->connected() && requests_->matched_readers() > 0 &&
           reply_reader_->matched_writers() > 0;
  }
  void send(uint64_t id, MqttRequestKind kind, const std::string& topic, const std::string& payload = {},
            uint8_t qos = 1) {
    MqttRequest r;
    r.request_id(id);
    r.kind(kind);
    r.topic(topic);
    r.payload(std::vector<uint8_t>(payload.begin(), payload.end()));
    r.qos(qos);
    requests_->write(r);
  }
  std::optional<MqttReply> reply(uint64_t id, std::chrono::milliseconds timeout = 10s) const {
    return replies_.wait_for([id](const MqttReply& r) { return r.request_id() == id; }, timeout);
  }
  // Broker traffic the gateway relayed onto DDS.
  bool saw_traffic(const std::string& topic, const std::string& payload) const {
    return traffic_
        .last([&](const MqttTraffic& t) {
          return t.direction() == MQTT_INBOUND && t.topic().to_string() == topic &&
                 std::string(t.payload().begin(), t.payload().end()) == payload;
        })
        .has_value();
  }

 private:
  Inbox<MqttReply> replies_;
  Inbox<MqttTraffic> traffic_;
  Inbox<MqttSubscriptions> subscriptions_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<MqttRequest>> requests_;
  std::unique_ptr<dds::Reader<MqttReply>> reply_reader_;
  std::unique_ptr<dds::Reader<MqttTraffic>> traffic_reader_;
  std::unique_ptr<dds::Reader<MqttSubscriptions>> subscriptions_reader_;
};

class GatewayRequestsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    group.start("gateway",
                {bin_path("slam-gateway"), "--domain", std::to_string(domain.id()), "--broker", url,
                 "--reconnect-max-s", "1", "--no-share"});  // a lone gateway: requests run from its start
    ASSERT_TRUE(wait_until([&] { return op.ready(); }, 20s)) << group.log("gateway");
    ASSERT_EQ(client.connect(), 0);
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "gateway log:\n" << group.log("gateway") << "\n";
  }
  // Asserts request `id` was answered ok.
  void expect_ok(uint64_t id) {
    const auto r = op.reply(id);
    ASSERT_TRUE(r) << "no reply to request " << id;
    EXPECT_TRUE(r->ok()) << "request " << id << ": " << r->message().to_string();
    EXPECT_EQ(r->message().to_string(), "");
  }
  // Asserts request `id` was refused with a message containing `why`.
  void expect_refused(uint64_t id, const std::string& why) {
    const auto r = op.reply(id);
    ASSERT_TRUE(r) << "no reply to request " << id;
    EXPECT_FALSE(r->ok()) << "request " << id;
    EXPECT_NE(r->message().to_string().find(why), std::string::npos) << r->message().to_string();
  }

  DomainLease domain;
  ProcessGroup group;
  int port = group.start_mosquitto();
  std::string url = "tcp://127.0.0.1:" + std::to_string(port);
  Operator op{domain.id()};
  MqttTestClient client{port, "gateway-requests-client"};
};

TEST_F(GatewayRequestsTest, PublishReachesASubscribedClientWithTheExactPayload) {
  ASSERT_TRUE(client.subscribe("ops/#"));
  const std::string payload("bin\0\x01\xff text", 11);
  op.send(1, MQTT_PUBLISH, "ops/hello", payload);
  expect_ok(1);
  ASSERT_TRUE(wait_until([&] { return !client.messages().empty(); }, 10s));
  const auto got = client.messages();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].topic, "ops/hello");
  EXPECT_EQ(got[0].payload, payload);
}

TEST_F(GatewayRequestsTest, SubscribeBringsTrafficOntoDdsAndUnsubscribeStopsIt) {
  op.send(1, MQTT_SUBSCRIBE, "site/+/temp");
  expect_ok(1);
  op.send(2, MQTT_SUBSCRIBE, "mark/#");
  expect_ok(2);
  // The broker's subscription ack may trail the reply: publish until the gateway relays it.
  ASSERT_TRUE(wait_until(
      [&] {
        EXPECT_TRUE(client.publish("site/a/temp", "21.5"));
        return wait_until([&] { return op.saw_traffic("site/a/temp", "21.5"); }, 200ms);
      },
      10s));

  op.send(3, MQTT_UNSUBSCRIBE, "site/+/temp");
  expect_ok(3);
  // Rounds of (filtered message, marker on a still-subscribed topic), in order on one connection:
  // once a marker arrives without its round's filtered message, unsubscribing took effect; the
  // rounds after that must stay quiet too.
  int quiet_rounds = 0;
  for (int round = 0; round < 50 && quiet_rounds < 3; ++round) {
    const std::string tag = std::to_string(round);
    ASSERT_TRUE(client.publish("site/a/temp", "after-" + tag));
    ASSERT_TRUE(client.publish("mark/x", tag));
    ASSERT_TRUE(wait_until([&] { return op.saw_traffic("mark/x", tag); }, 10s)) << "marker " << tag;
    const bool relayed = op.saw_traffic("site/a/temp", "after-" + tag);
    if (quiet_rounds > 0) {
      EXPECT_FALSE(relayed) << "relayed again after unsubscribing, round " << tag;
    }
    if (!relayed) ++quiet_rounds;
  }
  EXPECT_EQ(quiet_rounds, 3) << "traffic on the unsubscribed filter never stopped";
}

TEST_F(GatewayRequestsTest, BadTopicsFiltersAndQosAreRefusedWithAReason) {
  op.send(10, MQTT_SUBSCRIBE, "site/#/temp");
  op.send(11, MQTT_PUBLISH, "site/+/temp", "x");
  op.send(12, MQTT_UNSUBSCRIBE, "");
  op.send(13, MQTT_PUBLISH, "ops/qos", "x", 3);
  op.send(14, MQTT_SUBSCRIBE, "ops/fine");
  expect_refused(10, "#");
  expect_refused(11, "+");
  expect_refused(12, "empty");
  expect_refused(13, "qos 3");
  expect_ok(14);
  for (uint64_t id : {10, 11, 12, 13}) {
    const auto r = op.reply(id);
    ASSERT_TRUE(r);
    EXPECT_FALSE(r->message().to_string().empty()) << "request " << id << " refused without a reason";
  }
  EXPECT_TRUE(group.running("gateway"));
}

}  // namespace
}  // namespace slam::testkit
