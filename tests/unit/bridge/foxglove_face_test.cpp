#include "bridge/core/foxglove_face.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "bridge/core/ros_cdr.hpp"
#include "common/core/cell_class.hpp"

namespace slam::bridge {
namespace {

using nlohmann::json;
constexpr int64_t kSecond = 1'000'000'000;

struct Sent {
  ClientId client;
  bool binary;
  std::string bytes;
};

class RecordingSinks : public FrameSink, public OperatorSink {
 public:
  void send_text(ClientId c, const std::string& t) override { sent.push_back({c, false, t}); }
  void send_binary(ClientId c, const std::string& b) override { sent.push_back({c, true, b}); }
  void send_goal(const GoalCommand& g) override { goals.push_back(g); }
  void request_path(const PathCall& c) override { calls.push_back(c); }

  // The ops of the text frames sent so far.
  std::vector<std::string> ops() const {
    std::vector<std::string> out;
    for (const Sent& s : sent)
      if (!s.binary) out.push_back(json::parse(s.bytes)["op"]);
    return out;
  }
  // Message data frames for subscription `sub`.
  std::vector<std::string> payloads(uint32_t sub) const {
    std::vector<std::string> out;
    for (const Sent& s : sent)
      if (s.binary && s.bytes[0] == 0x01 && static_cast<uint8_t>(s.bytes[1]) == sub)
        out.push_back(s.bytes.substr(13));
    return out;
  }

  std::vector<Sent> sent;
  std::vector<GoalCommand> goals;
  std::vector<PathCall> calls;
};

class FoxgloveFaceTest : public ::testing::Test {
 protected:
  FoxgloveFaceTest() : face_(ChannelPeriods{}, "session", sinks_, sinks_, counters_) {}

  void subscribe(ClientId client, uint32_t sub, Channel channel) {
    face_.receive_text(client,
                       json{{"op", "subscribe"},
                            {"subscriptions", {{{"id", sub}, {"channelId", static_cast<uint32_t>(channel)}}}}}
                           .dump());
  }
  void robot_at(double x) { fleet_.ingest(msg::RobotPose{"r1", Pose{x, 0, 0}, true, true, 0}); }

  // A kSide x kSide grid of 4 x 4 tiles, every cell `cell`.
  static constexpr int32_t kSide = 128, kTile = 32;
  static msg::GridSnapshot snapshot(uint64_t version, uint8_t cell) {
    return {1, version, 0, msg::GridInfo{kSide, kSide, 0.1, {0, 0}, 0.0},
            std::vector<uint8_t>(static_cast<size_t>(kSide) * kSide, cell)};
  }
  // A patch of whole raw tiles (numbered row by row), every cell occupied.
  static msg::GridTiles tiles(uint64_t version, std::vector<uint32_t> numbers) {
    std::vector<uint8_t> data(numbers.size() * kTile * kTile, kCellOccupied);
    return {1, version, 0, kTile, 0, std::move(numbers), std::move(data)};
  }

  Counters counters_;
  RecordingSinks sinks_;
  FoxgloveFace face_;
  FleetModel fleet_{10};
  MapView map_;
};

TEST_F(FoxgloveFaceTest, GreetsAClientWithServerInfoChannelsAndThePathService) {
  face_.connect(7);
  EXPECT_EQ(sinks_.ops(), (std::vector<std::string>{"serverInfo", "advertise", "advertiseServices"}));
  const json info = json::parse(sinks_.sent[0].bytes);
  EXPECT_EQ(info["capabilities"], (json{"clientPublish", "services"}));
  const json advertised = json::parse(sinks_.sent[1].bytes);
  EXPECT_EQ(advertised["channels"].size(), channel_table().size());
  EXPECT_EQ(face_.clients(), 1u);
}

TEST_F(FoxgloveFaceTest, SendsOnlySubscribedChannelsOncePerPeriodWhenChanged) {
  face_.connect(1);
  robot_at(1.0);
  face_.publish(fleet_, map_, 0, 0);
  EXPECT_TRUE(sinks_.payloads(5).empty());  // nobody subscribed yet

  subscribe(1, 5, Channel::Robots);
  face_.publish(fleet_, map_, 1 * kSecond, 0);
  ASSERT_EQ(sinks_.payloads(5).size(), 1u);

  robot_at(2.0);
  face_.publish(fleet_, map_, 1 * kSecond + kSecond / 10, 0);  // within the 0.2 s period
  EXPECT_EQ(sinks_.payloads(5).size(), 1u);
  face_.publish(fleet_, map_, 2 * kSecond, 0);
  ASSERT_EQ(sinks_.payloads(5).size(), 2u);
  face_.publish(fleet_, map_, 3 * kSecond, 0);  // nothing changed
  EXPECT_EQ(sinks_.payloads(5).size(), 2u);
  EXPECT_EQ(json::parse(sinks_.payloads(5)[1])["entities"][0]["arrows"][0]["pose"]["position"]["x"], 2.0);
}

TEST_F(FoxgloveFaceTest, ALateSubscriberGetsTheLastMessageAtOnce) {
  face_.connect(1);
  face_.connect(2);
  subscribe(1, 5, Channel::Robots);
  robot_at(1.0);
  face_.publish(fleet_, map_, 0, 0);
  subscribe(2, 9, Channel::Robots);
  ASSERT_EQ(sinks_.payloads(9).size(), 1u);
  EXPECT_EQ(sinks_.payloads(9)[0], sinks_.payloads(5)[0]);
}

TEST_F(FoxgloveFaceTest, UnsubscribedChannelsStopAndDisconnectedClientsGetNothing) {
  face_.connect(1);
  subscribe(1, 5, Channel::Robots);
  face_.receive_text(1, R"({"op": "unsubscribe", "subscriptionIds": [5]})");
  robot_at(1.0);
  face_.publish(fleet_, map_, 0, 0);
  EXPECT_TRUE(sinks_.payloads(5).empty());
  face_.disconnect(1);
  EXPECT_EQ(face_.clients(), 0u);
}

TEST_F(FoxgloveFaceTest, TheRosMapChannelIsCdrOfTheWholeGridWithItsRos2msgDefinition) {
  const auto& table = channel_table();
  const auto ros = std::find_if(table.begin(), table.end(), [](const foxglove::ChannelInfo& c) {
    return c.id == static_cast<uint32_t>(Channel::RosMap);
  });
  ASSERT_NE(ros, table.end());
  EXPECT_EQ(ros->encoding, "cdr");
  EXPECT_EQ(ros->schema_encoding, "ros2msg");
  EXPECT_EQ(ros->schema_name, "nav_msgs/msg/OccupancyGrid");
  EXPECT_EQ(ros->schema, kOccupancyGridDefinition);

  face_.connect(1);
  subscribe(1, 3, Channel::RosMap);
  msg::GridSnapshot s{1, 1, 0, msg::GridInfo{4, 2, 0.1, {0, 0}, 0.0}, std::vector<uint8_t>(8, kCellOccupied)};
  ASSERT_TRUE(map_.ingest(std::move(s)));
  face_.publish(fleet_, map_, 0, 0);
  ASSERT_EQ(sinks_.payloads(3).size(), 1u);
  EXPECT_EQ(sinks_.payloads(3)[0], occupancy_grid_cdr(occupancy_grid(map_.geometry(), map_.cells(), 0)));
}

TEST_F(FoxgloveFaceTest, SendsAlertsWhenOneChanged) {
  face_.connect(1);
  subscribe(1, 4, Channel::Alerts);
  fleet_.ingest(
      msg::Alert{"offline/r1", msg::AlertKind::RobotOffline, "r1", true, 0, 0, "r1 is offline", "p1"});
  face_.publish(fleet_, map_, 0, 0);
  ASSERT_EQ(sinks_.payloads(4).size(), 1u);
  EXPECT_EQ(json::parse(sinks_.payloads(4)[0])["alerts"][0]["alert_id"], "offline/r1");
  face_.publish(fleet_, map_, 10 * kSecond, 0);  // nothing changed
  EXPECT_EQ(sinks_.payloads(4).size(), 1u);
}

TEST_F(FoxgloveFaceTest, SendsTheWholeMapThenOnlyTheChangedRegion) {
  face_.connect(1);
  subscribe(1, 1, Channel::Map);
  subscribe(1, 2, Channel::MapUpdates);
  ASSERT_TRUE(map_.ingest(snapshot(1, 0)));
  face_.publish(fleet_, map_, 0, 0);
  ASSERT_EQ(sinks_.payloads(1).size(), 1u);
  EXPECT_EQ(json::parse(sinks_.payloads(1)[0])["column_count"], kSide);
  EXPECT_TRUE(sinks_.payloads(2).empty());  // the whole grid covered the change

  ASSERT_TRUE(map_.ingest(tiles(2, {5})));
  face_.publish(fleet_, map_, 1 * kSecond, 0);  // the whole grid is not due for 5 s: the region goes
  EXPECT_EQ(sinks_.payloads(1).size(), 1u);
  ASSERT_EQ(sinks_.payloads(2).size(), 1u);
  EXPECT_EQ(json::parse(sinks_.payloads(2)[0])["column_count"], kTile);
}

TEST_F(FoxgloveFaceTest, AChangedRegionOverAQuarterOfTheGridWaitsForTheWholeGrid) {
  face_.connect(1);
  subscribe(1, 1, Channel::Map);
  subscribe(1, 2, Channel::MapUpdates);
  ASSERT_TRUE(map_.ingest(snapshot(1, 0)));
  face_.publish(fleet_, map_, 0, 0);
  ASSERT_EQ(sinks_.payloads(1).size(), 1u);

  // Two tiles in opposite corners: their bounding box is the whole grid.
  ASSERT_TRUE(map_.ingest(tiles(2, {0, 15})));
  face_.publish(fleet_, map_, 1 * kSecond, 0);
  face_.publish(fleet_, map_, 2 * kSecond, 0);
  EXPECT_TRUE(sinks_.payloads(2).empty());
  EXPECT_EQ(sinks_.payloads(1).size(), 1u);

  face_.publish(fleet_, map_, 5 * kSecond, 0);  // the whole grid is due: it carries the change
  ASSERT_EQ(sinks_.payloads(1).size(), 2u);
  EXPECT_TRUE(sinks_.payloads(2).empty());
  EXPECT_TRUE(map_.changed().empty());
}

TEST_F(FoxgloveFaceTest, AGoalPublishedOnTheGoalChannelReachesTheFleet) {
  face_.connect(1);
  face_.receive_text(1, R"({"op": "advertise", "channels": [{"id": 4, "topic": "/goal", "encoding": "json",
                            "schemaName": "slam.Goal"}]})");
  face_.receive_binary(1, std::string("\x01\x04\x00\x00\x00", 5) + R"({"robot_id": "r1", "x": 1, "y": 2})");
  ASSERT_EQ(sinks_.goals.size(), 1u);
  EXPECT_EQ(sinks_.goals[0].robot_id, "r1");
  EXPECT_EQ(sinks_.goals[0].target, (Vec2{1, 2}));
}

TEST_F(FoxgloveFaceTest, BadClientInputIsAnsweredWithAWarning) {
  face_.connect(1);
  sinks_.sent.clear();
  face_.receive_binary(1, std::string("\x01\x04\x00\x00\x00{}", 7));  // channel 4 was never advertised
  face_.receive_text(1, "{oops");
  face_.receive_text(1, R"({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": 99}]})");
  EXPECT_EQ(sinks_.ops(), (std::vector<std::string>{"status", "status", "status"}));
  EXPECT_TRUE(sinks_.goals.empty());
  EXPECT_EQ(counters_.get("client_errors").load(), 3);
}

TEST_F(FoxgloveFaceTest, APathCallIsAnsweredWithThePlannersPathOrAFailure) {
  face_.connect(1);
  sinks_.sent.clear();
  const std::string request = R"({"start": {"x": 0, "y": 0}, "goal": {"x": 1, "y": 1}})";
  std::string frame("\x02\x01\x00\x00\x00\x2a\x00\x00\x00\x04\x00\x00\x00json", 17);
  face_.receive_binary(1, frame + request);
  ASSERT_EQ(sinks_.calls.size(), 1u);
  EXPECT_EQ(sinks_.calls[0].call_id, 42u);
  EXPECT_EQ(sinks_.calls[0].query.goal, (Vec2{1, 1}));

  face_.answer(sinks_.calls[0], msg::PathReply{7, msg::PlanStatus::Ok, "", {{0, 0}, {1, 1}}, 1.41, 0.0});
  ASSERT_EQ(sinks_.sent.size(), 1u);
  EXPECT_TRUE(sinks_.sent[0].binary);
  EXPECT_EQ(sinks_.sent[0].bytes[0], 0x03);
  EXPECT_EQ(json::parse(sinks_.sent[0].bytes.substr(17))["status"], "ok");

  face_.answer(sinks_.calls[0], std::nullopt);
  EXPECT_EQ(sinks_.ops(), (std::vector<std::string>{"serviceCallFailure"}));
}

}  // namespace
}  // namespace slam::bridge
