// slam-gateway executing operator MQTT requests from DDS (MqttRequest) against a real mosquitto:
// publish reaches a subscribed client byte for byte, subscribe brings broker traffic onto the
// MqttTraffic topic and unsubscribe stops it, bad topics and filters are refused; every request
// is answered with an MqttReply carrying its id.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "process_group.hpp"
#include "test_mqtt_client.hpp"

namespace slam::testkit {
namespace {

template <class T>
T take(Result<T> r) {
  if (!r) {
    ADD_FAILURE() << r.message();
    return T{};
  }
  return std::move(*r);
}

// The viewer's side of the gateway: requests out, replies and traffic in.
class Operator {
 public:
  explicit Operator(int domain) {
    participant_ = take(dds::Participant::create(domain, "gateway-requests-test"));
    requests_ = take(dds::make_writer(*participant_, dds::kMqttRequest));
    replies_ = take(dds::make_reader(*participant_, dds::kMqttReply, [this](const MqttReply& r, const auto&) {
      std::lock_guard lock(mutex_);
      replies_seen_[r.request_id()] = r;
    }));
    traffic_ =
        take(dds::make_reader(*participant_, dds::kMqttTraffic, [this](const MqttTraffic& t, const auto&) {
          if (t.direction() != MQTT_INBOUND) return;
          std::lock_guard lock(mutex_);
          traffic_seen_.push_back(
              {t.topic().to_string(), std::string(t.payload().begin(), t.payload().end())});
        }));
    subscriptions_ = take(dds::make_reader(*participant_, dds::kMqttSubscriptions,
                                           [this](const MqttSubscriptions& s, const auto&) {
                                             std::lock_guard lock(mutex_);
                                             connected_ = s.connected();
                                           }));
  }

  bool ready() {
    {
      std::lock_guard lock(mutex_);
      if (!connected_) return false;
    }
    return requests_->matched_readers() > 0 && replies_->matched_writers() > 0;
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
  std::optional<MqttReply> reply(uint64_t id, std::chrono::milliseconds timeout = 10s) {
    std::optional<MqttReply> out;
    wait_until(
        [&] {
          std::lock_guard lock(mutex_);
          const auto it = replies_seen_.find(id);
          if (it != replies_seen_.end()) out = it->second;
          return out.has_value();
        },
        timeout);
    return out;
  }
  bool saw_traffic(const std::string& topic, const std::string& payload) {
    std::lock_guard lock(mutex_);
    for (const MqttMessage& m : traffic_seen_)
      if (m.topic == topic && m.payload == payload) return true;
    return false;
  }

 private:
  std::mutex mutex_;
  std::map<uint64_t, MqttReply> replies_seen_;
  std::vector<MqttMessage> traffic_seen_;
  bool connected_ = false;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Writer<MqttRequest>> requests_;
  std::unique_ptr<dds::Reader<MqttReply>> replies_;
  std::unique_ptr<dds::Reader<MqttTraffic>> traffic_;
  std::unique_ptr<dds::Reader<MqttSubscriptions>> subscriptions_;
};

class GatewayRequestsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    group.start("gateway", {bin_path("slam-gateway"), "--domain", std::to_string(domain.id()), "--broker",
                            url, "--reconnect-max-s", "1"});
    ASSERT_TRUE(wait_until([&] { return op.ready(); }, 20s)) << group.log("gateway");
    ASSERT_TRUE(client.connect());
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
  TestMqttClient client{url, "gateway-requests-client"};
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
