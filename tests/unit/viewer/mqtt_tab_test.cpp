// MqttTab: subscribe, unsubscribe and publish (SLAM v1 pairs, raw hex, text) send the right
// request and track it for the gateway's reply; bad input shows an error and sends nothing; the
// log view filters rows.
#include "viewer/core/mqtt_tab.hpp"

#include <gtest/gtest.h>

#include "fake_command_sink.hpp"

namespace slam::viewer {
namespace {

class MqttTabTest : public ::testing::Test {
 protected:
  ViewerState state{100};
  FakeCommandSink sink;
  MqttTab tab;
};

TEST_F(MqttTabTest, SubscribeSendsTheFilterAndWaitsForTheReply) {
  tab.filter = "v1/robot/+/adv";
  tab.subscribe(state, sink, 5);
  ASSERT_EQ(sink.mqtt.size(), 1u);
  EXPECT_EQ(sink.mqtt[0].kind, MqttRequestKind::Subscribe);
  EXPECT_EQ(sink.mqtt[0].topic, "v1/robot/+/adv");
  EXPECT_TRUE(tab.error.empty());
  ASSERT_TRUE(state.mqtt_requests.last());
  EXPECT_EQ(state.mqtt_requests.last()->id, sink.last_id);
  EXPECT_EQ(state.mqtt_requests.last()->what, "subscribe v1/robot/+/adv");
  EXPECT_EQ(state.mqtt_requests.last()->state, RequestState::Waiting);
}

TEST_F(MqttTabTest, SubscribeWithAnEmptyFilterShowsAnErrorAndSendsNothing) {
  tab.filter.clear();
  tab.subscribe(state, sink, 0);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
  EXPECT_FALSE(state.mqtt_requests.last());
}

TEST_F(MqttTabTest, SubscribeWithATooLongFilterIsRefused) {
  tab.filter.assign(kMaxMqttTopic + 1, 'a');
  tab.subscribe(state, sink, 0);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(MqttTabTest, UnsubscribeSendsTheListedFilter) {
  tab.unsubscribe(state, sink, "v1/robot/#", 0);
  ASSERT_EQ(sink.mqtt.size(), 1u);
  EXPECT_EQ(sink.mqtt[0].kind, MqttRequestKind::Unsubscribe);
  EXPECT_EQ(sink.mqtt[0].topic, "v1/robot/#");
  EXPECT_EQ(state.mqtt_requests.last()->what, "unsubscribe v1/robot/#");
}

TEST_F(MqttTabTest, UnsubscribeOfAnEmptyFilterIsRefused) {
  tab.unsubscribe(state, sink, "", 0);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(MqttTabTest, PublishSlamMessageEncodesV1Pairs) {
  tab.topic = "v1/server/r1/cmd";
  tab.payload_kind = PayloadKind::V1Pairs;
  tab.payload = "1,2 -3,4";
  tab.qos = 1;
  tab.retain = true;
  tab.publish(state, sink, 0);
  ASSERT_EQ(sink.mqtt.size(), 1u);
  const MqttRequestCommand& c = sink.mqtt[0];
  EXPECT_EQ(c.kind, MqttRequestKind::Publish);
  EXPECT_EQ(c.topic, "v1/server/r1/cmd");
  EXPECT_EQ(c.payload, (std::vector<uint8_t>{1, 0, 2, 0, 0xfd, 0xff, 4, 0}));  // int16 LE pairs
  EXPECT_EQ(c.qos, 1);
  EXPECT_TRUE(c.retain);
  EXPECT_EQ(state.mqtt_requests.last()->what, "publish 8 octets to v1/server/r1/cmd");
}

TEST_F(MqttTabTest, PublishRawHex) {
  tab.payload_kind = PayloadKind::Hex;
  tab.payload = "0a ff, 0x10";
  tab.publish(state, sink, 0);
  ASSERT_EQ(sink.mqtt.size(), 1u);
  EXPECT_EQ(sink.mqtt[0].payload, (std::vector<uint8_t>{0x0a, 0xff, 0x10}));
  EXPECT_EQ(sink.mqtt[0].qos, 0);
  EXPECT_FALSE(sink.mqtt[0].retain);
}

TEST_F(MqttTabTest, PublishText) {
  tab.payload_kind = PayloadKind::Text;
  tab.payload = "hi";
  tab.publish(state, sink, 0);
  ASSERT_EQ(sink.mqtt.size(), 1u);
  EXPECT_EQ(sink.mqtt[0].payload, (std::vector<uint8_t>{'h', 'i'}));
}

TEST_F(MqttTabTest, PublishBadHexShowsAnErrorAndSendsNothing) {
  tab.payload_kind = PayloadKind::Hex;
  tab.payload = "0a zz";
  tab.publish(state, sink, 0);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_NE(tab.error.find("publish"), std::string::npos);
  EXPECT_FALSE(state.mqtt_requests.last());
}

TEST_F(MqttTabTest, PublishOutOfRangePairIsRefused) {
  tab.payload_kind = PayloadKind::V1Pairs;
  tab.payload = "40000,1";  // beyond int16
  tab.publish(state, sink, 0);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(MqttTabTest, PublishToAnEmptyTopicIsRefused) {
  tab.topic.clear();
  tab.payload_kind = PayloadKind::Text;
  tab.publish(state, sink, 0);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(MqttTabTest, PublishToAWildcardTopicIsRefused) {
  tab.topic = "v1/server/+/cmd";
  tab.payload_kind = PayloadKind::Text;
  tab.publish(state, sink, 0);
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(MqttTabTest, PublishWithQosOutOfRangeIsRefused) {
  tab.payload_kind = PayloadKind::Text;
  for (int qos : {-1, 3}) {
    tab.qos = qos;
    tab.publish(state, sink, 0);
  }
  EXPECT_EQ(sink.total(), 0u);
  EXPECT_FALSE(tab.error.empty());
}

TEST_F(MqttTabTest, ValidPublishClearsTheLastError) {
  tab.topic.clear();
  tab.publish(state, sink, 0);
  ASSERT_FALSE(tab.error.empty());
  tab.topic = "a/b";
  tab.payload_kind = PayloadKind::Text;
  tab.publish(state, sink, 0);
  EXPECT_EQ(sink.mqtt.size(), 1u);
  EXPECT_TRUE(tab.error.empty());
}

TEST_F(MqttTabTest, RefusedSendShowsAnErrorAndTracksNothing) {
  sink.refuse = true;
  tab.subscribe(state, sink, 0);
  EXPECT_NE(tab.error.find("NOT sent"), std::string::npos);
  EXPECT_FALSE(state.mqtt_requests.last());
}

TEST_F(MqttTabTest, GatewayReplyShowsOnTheTab) {
  tab.subscribe(state, sink, 0);
  IntakeBatch batch;
  batch.mqtt_replies.push_back({{sink.last_id, false, "bad filter"}});
  state.ingest(batch, 1);
  EXPECT_EQ(state.mqtt_requests.last()->state, RequestState::Failed);
  EXPECT_EQ(state.mqtt_requests.last()->message, "bad filter");
}

TEST_F(MqttTabTest, ClearEmptiesTheLog) {
  state.mqtt.push(MqttEntry{1, 0, true, "a", {1}, 1});
  MqttTab::clear_log(state);
  EXPECT_EQ(state.mqtt.size(), 0u);
}

TEST(MqttLogView, ShowsByDirectionAndTopicSearch) {
  MqttLogView view;
  const MqttEntry in{1, 0, true, "v1/robot/r1/adv", {}, 0};
  const MqttEntry out{2, 0, false, "v1/server/r1/cmd", {}, 0};
  EXPECT_FALSE(view.filtered());
  EXPECT_TRUE(view.shows(in));
  EXPECT_TRUE(view.shows(out));
  view.show_outbound = false;
  EXPECT_TRUE(view.filtered());
  EXPECT_TRUE(view.shows(in));
  EXPECT_FALSE(view.shows(out));
  view.show_outbound = true;
  view.show_inbound = false;
  EXPECT_FALSE(view.shows(in));
  view.show_inbound = true;
  view.search = "server";
  EXPECT_FALSE(view.shows(in));
  EXPECT_TRUE(view.shows(out));
}

TEST(MqttLogView, PayloadDecodedOrHex) {
  MqttLogView view;
  const MqttEntry e{1, 0, true, "some/topic", {'o', 'k'}, 2};
  EXPECT_EQ(view.payload_text(e), "ok");
  view.decoded = false;
  EXPECT_EQ(view.payload_text(e), "6f 6b");
}

}  // namespace
}  // namespace slam::viewer
