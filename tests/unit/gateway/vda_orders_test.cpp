// VdaOrders: the planner's path as an order released up to its waypoint, updates stitched at the last
// base node, halts as startPause (resumed by stopPause or dropped by cancelOrder), and the robot's state
// deciding what comes next.
#include "gateway/core/vda_orders.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace slam::gateway {
namespace {

using protocol::Point;
using Json = nlohmann::json;

constexpr Instant kStart{1'764'327'042'000'000'000, 5'000'000'000};
const protocol::VdaAddress kAddress{protocol::VdaTopic::State, "Acme", "agv-1"};

class VdaOrdersTest : public ::testing::Test {
 protected:
  VdaOrdersTest() { hear(state()); }

  // A state: the order it drives (empty: none), nodes left, whether it drives and is paused.
  static protocol::VdaMessage state(std::string order_id = "", std::size_t nodes_left = 0,
                                    bool driving = false, bool paused = false) {
    protocol::VdaMessage m;
    m.topic = protocol::VdaTopic::State;
    m.has_position = m.position_initialized = true;
    m.map_id = "hall";
    m.order_id = std::move(order_id);
    m.node_states = nodes_left;
    m.driving = driving;
    m.paused = paused;
    return m;
  }
  std::optional<VdaRejection> hear(const protocol::VdaMessage& m) {
    bool known = false;
    auto rejection = orders.take_message("Acme:agv-1", kAddress, m, known);
    EXPECT_TRUE(known);
    return rejection;
  }
  // Every message the command produced, parsed, by topic's last level ("order", "instantActions").
  std::vector<std::pair<std::string, Json>> commands(Point position, std::vector<Point> path) {
    const auto s = orders.command("Acme:agv-1", position, path, now, out);
    EXPECT_TRUE(s) << s.message();
    std::vector<std::pair<std::string, Json>> sent;
    for (const OutboundMessage& m : out.view())
      sent.emplace_back(m.topic.substr(m.topic.rfind('/') + 1), Json::parse(m.payload));
    return sent;
  }
  // The one message the command produced, parsed; null when there was none.
  Json command(Point position, std::vector<Point> path) {
    const auto sent = commands(position, std::move(path));
    if (sent.empty()) return nullptr;
    EXPECT_EQ(sent.size(), 1u);
    topic = out.messages[0].topic;
    return sent[0].second;
  }
  static std::vector<std::string> action_types(const Json& instant_actions) {
    std::vector<std::string> types;
    for (const Json& a : instant_actions["instantActions"]) types.push_back(a["actionType"]);
    return types;
  }

  // The instant actions sent again at `now` plus `seconds` (by the last level of their topics' type),
  // and the lines of those given up.
  std::vector<Json> resent_after(double seconds) {
    now.mono_ns += static_cast<std::int64_t>(seconds * 1e9);
    now.wall_ns += static_cast<std::int64_t>(seconds * 1e9);
    orders.resend(now, resent, given_up);
    std::vector<Json> sent;
    for (const OutboundMessage& m : resent) sent.push_back(Json::parse(m.payload));
    return sent;
  }

  VdaOrders orders{protocol::VdaTree{}, protocol::CodecLimits{}};
  Instant now = kStart;
  CommandMessages out;
  std::vector<OutboundMessage> resent;
  std::vector<std::string> given_up;
  std::string topic;
};

TEST_F(VdaOrdersTest, ARobotNeverHeardGetsNothing) {
  const std::vector<Point> path{{1, 1}};
  const auto s = orders.command("Acme:agv-9", Point{0, 0}, path, now, out);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.reason(), protocol::RejectReason::UnknownRobot);
  EXPECT_EQ(out.count, 0u);
}

TEST_F(VdaOrdersTest, FirstPathStartsWhereTheRobotStandsReleasedUpToTheWaypoint) {
  const Json order = command({0, 0}, {{2, 0}, {2, 3}, {5, 3}});
  EXPECT_EQ(topic, "uagv/v2/Acme/agv-1/order");
  EXPECT_EQ(order["headerId"], 0);
  EXPECT_EQ(order["orderUpdateId"], 0);
  ASSERT_EQ(order["nodes"].size(), 4u);
  EXPECT_EQ(order["nodes"][0]["nodePosition"]["x"], 0.0);
  EXPECT_EQ(order["nodes"][0]["nodePosition"]["mapId"], "hall");
  EXPECT_EQ(order["nodes"][1]["nodePosition"]["x"], 2.0);
  EXPECT_EQ(order["nodes"][1]["released"], true);
  EXPECT_EQ(order["nodes"][2]["released"], false);
  EXPECT_EQ(order["nodes"][3]["sequenceId"], 6);
  EXPECT_EQ(order["edges"].size(), 3u);
}

TEST_F(VdaOrdersTest, AnOrderIsSentAgainWithBackoffUnderTheNextHeaderIdUntilTheStateShowsItTaken) {
  const Json first = command({0, 0}, {{2, 0}, {2, 3}});
  EXPECT_TRUE(command({0.5, 0}, {{2.001, 0}, {2, 3}}).is_null()) << "the same waypoint: the order stands";
  EXPECT_TRUE(resent_after(0.9).empty()) << "not due yet";
  const auto again = resent_after(0.1);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0]["headerId"], 1);
  EXPECT_EQ(again[0]["orderId"], first["orderId"]);
  EXPECT_EQ(again[0]["orderUpdateId"], 0);
  EXPECT_EQ(again[0]["nodes"], first["nodes"]);
  EXPECT_TRUE(resent_after(1.9).empty()) << "the wait doubles: 2 s after the second send";
  EXPECT_EQ(resent_after(0.1).size(), 1u);
  hear(state(first["orderId"], 2, true));
  EXPECT_TRUE(resent_after(100).empty()) << "taken";
  EXPECT_TRUE(given_up.empty());
}

TEST_F(VdaOrdersTest, AnOrderNeverTakenIsGivenUpAfterItsSendsAsIfRejected) {
  command({0, 0}, {{2, 0}});
  std::size_t sends = 1;
  for (int i = 0; i < 10 && given_up.empty(); ++i) sends += resent_after(10).size();
  EXPECT_EQ(sends, 4u);
  ASSERT_EQ(given_up.size(), 1u);
  EXPECT_NE(given_up[0].find("not taken after 4 sends"), std::string::npos) << given_up[0];
  const Json fresh = command({0, 0}, {{2, 0}});
  EXPECT_EQ(fresh["orderUpdateId"], 0) << "the next path starts a new order";
}

TEST_F(VdaOrdersTest, TheNextWaypointExtendsTheOrderFromItsLastBaseNode) {
  const Json first = command({0, 0}, {{2, 0}, {2, 3}, {5, 3}});
  hear(state(first["orderId"], 3, true));
  const Json update = command({1.9, 0}, {{2, 3}, {5, 3}});
  EXPECT_EQ(update["orderId"], first["orderId"]);
  EXPECT_EQ(update["orderUpdateId"], 1);
  ASSERT_EQ(update["nodes"].size(), 3u);
  // The stitching node is the previous base's last, id and sequence id alike.
  EXPECT_EQ(update["nodes"][0]["nodeId"], first["nodes"][1]["nodeId"]);
  EXPECT_EQ(update["nodes"][0]["sequenceId"], 2);
  EXPECT_EQ(update["nodes"][1]["sequenceId"], 4);
  EXPECT_EQ(update["nodes"][1]["released"], true);
  EXPECT_EQ(update["nodes"][2]["released"], false);
}

TEST_F(VdaOrdersTest, AHoldPausesTheRobotAndItsReleaseResumesTheSameOrder) {
  const Json first = command({0, 0}, {{4, 0}, {4, 3}});
  hear(state(first["orderId"], 2, true));
  const Json pause = command({1, 0}, {{1.1, 0}});
  EXPECT_EQ(topic, "uagv/v2/Acme/agv-1/instantActions");
  EXPECT_EQ(action_types(pause), std::vector<std::string>{"startPause"});
  EXPECT_EQ(pause["headerId"], 0);
  hear(state(first["orderId"], 2, false));
  EXPECT_TRUE(command({1, 0}, {{1.1, 0}}).is_null()) << "held already: the hold again sends nothing";
  // Released: the planner's waypoint again, so the order it took goes on as sent: the pause ends.
  const Json resumed = command({1, 0}, {{4, 0}, {4, 3}});
  EXPECT_EQ(topic, "uagv/v2/Acme/agv-1/instantActions");
  EXPECT_EQ(action_types(resumed), std::vector<std::string>{"stopPause"});
  EXPECT_EQ(resumed["headerId"], 1);
  hear(state(first["orderId"], 2, true));
  EXPECT_TRUE(command({1.5, 0}, {{4, 0}, {4, 3}}).is_null()) << "the pause is over, the order taken";
}

TEST_F(VdaOrdersTest, AStopThenAGoalElsewhereCancelsTheHeldOrderAndStartsANewOneOnceItIsDone) {
  const Json first = command({0, 0}, {{4, 0}, {4, 3}});
  hear(state(first["orderId"], 2, true));
  EXPECT_EQ(action_types(command({1, 0}, {{1.1, 0}})), std::vector<std::string>{"startPause"});
  hear(state(first["orderId"], 2, false, true));
  // A new goal: the held order is not driven on.
  const Json cancel = command({1, 0}, {{0, 2}, {0, 5}});
  EXPECT_EQ(topic, "uagv/v2/Acme/agv-1/instantActions");
  EXPECT_EQ(action_types(cancel), std::vector<std::string>{"cancelOrder"});
  EXPECT_TRUE(command({1, 0}, {{0, 2}, {0, 5}}).is_null()) << "the cancel is still under way";
  // Done, and its pause ended with the order.
  hear(state(first["orderId"], 0, false, false));
  const Json fresh = command({1, 0}, {{0, 2}, {0, 5}});
  EXPECT_EQ(topic, "uagv/v2/Acme/agv-1/order");
  EXPECT_NE(fresh["orderId"], first["orderId"]);
  EXPECT_EQ(fresh["orderUpdateId"], 0);
  EXPECT_EQ(fresh["nodes"][0]["nodePosition"]["x"], 1.0);
}

TEST_F(VdaOrdersTest, ARobotStillPausedAfterTheCancelGetsStopPauseWithTheNewOrder) {
  const Json first = command({0, 0}, {{4, 0}, {4, 3}});
  hear(state(first["orderId"], 2, true));
  command({1, 0}, {{1.1, 0}});
  hear(state(first["orderId"], 2, false, true));
  EXPECT_EQ(action_types(command({1, 0}, {{0, 2}})), std::vector<std::string>{"cancelOrder"});
  hear(state(first["orderId"], 0, false, true));
  const auto sent = commands({1, 0}, {{0, 2}});
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].first, "order");
  EXPECT_NE(sent[0].second["orderId"], first["orderId"]);
  EXPECT_EQ(action_types(sent[1].second), std::vector<std::string>{"stopPause"});
}

TEST_F(VdaOrdersTest, AnInstantActionIsSentAgainWithBackoffUntilTheStateListsIt) {
  const Json first = command({0, 0}, {{4, 0}, {4, 3}});
  hear(state(first["orderId"], 2, true));
  const Json pause = command({1, 0}, {{1.1, 0}});
  const Json action = pause["instantActions"][0];
  EXPECT_TRUE(resent_after(0.9).empty()) << "not due yet";
  auto again = resent_after(0.1);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0]["instantActions"][0], action) << "the same action, under its id";
  EXPECT_EQ(again[0]["headerId"], pause["headerId"].get<int>() + 1);
  EXPECT_TRUE(resent_after(1.9).empty()) << "the wait doubles: 2 s after the second send";
  EXPECT_EQ(resent_after(0.1).size(), 1u);
  protocol::VdaMessage taken = state(first["orderId"], 2, false, true);
  taken.action_states.push_back({action["actionId"], "FINISHED"});
  hear(taken);
  EXPECT_TRUE(resent_after(100).empty()) << "listed: taken";
  EXPECT_TRUE(given_up.empty());
}

TEST_F(VdaOrdersTest, AnInstantActionNeverListedIsGivenUpAfterItsSends) {
  const Json first = command({0, 0}, {{4, 0}, {4, 3}});
  hear(state(first["orderId"], 2, true));
  command({1, 0}, {{1.1, 0}});
  std::size_t sends = 1;
  for (int i = 0; i < 10 && given_up.empty(); ++i) sends += resent_after(10).size();
  EXPECT_EQ(sends, 4u);
  ASSERT_EQ(given_up.size(), 1u);
  EXPECT_NE(given_up[0].find("startPause"), std::string::npos) << given_up[0];
  EXPECT_NE(given_up[0].find("Acme:agv-1"), std::string::npos) << given_up[0];
  EXPECT_TRUE(resent_after(100).empty());
}

TEST_F(VdaOrdersTest, AHaltOfARobotWithoutAnOrderSendsNothing) {
  hear(state("", 0, true));
  EXPECT_TRUE(command({1, 0}, {{1.1, 0}}).is_null());
}

TEST_F(VdaOrdersTest, AStandingRobotIsSentThereNotCancelled) {
  command({1, 1}, {{1.05, 1.1}});
  EXPECT_EQ(topic, "uagv/v2/Acme/agv-1/order");
}

TEST_F(VdaOrdersTest, TheNodeItDrivesToMovedByACorrectionIsNoHalt) {
  const Json order = command({0, 0}, {{2, 0}});
  hear(state(order["orderId"], 1, true));
  // The last leg: the waypoint alone, a millimetre nearer than the node, 0.2 m ahead.
  EXPECT_TRUE(command({1.8, 0}, {{1.999, 0}}).is_null()) << "the order stands: no startPause";
}

TEST_F(VdaOrdersTest, AShortLastLegIsADestinationNotAHalt) {
  // Nearly at its base's last node and on to a last waypoint 0.4 m further.
  const Json order = command({0, 0}, {{2, 0}, {2.3, 0.3}});
  hear(state(order["orderId"], 1, true));
  const Json next = command({1.95, 0}, {{2.3, 0.3}});
  EXPECT_EQ(topic, "uagv/v2/Acme/agv-1/order");
  EXPECT_EQ(next["orderUpdateId"], 1);
}

TEST_F(VdaOrdersTest, ARejectionIsReportedOnceAndTheNextPathStartsAnOrderAfresh) {
  const Json first = command({0, 0}, {{2, 0}});
  protocol::VdaMessage rejected = state();
  rejected.errors.push_back(
      {"noRouteError", "WARNING", "first node not within deviation range", first["orderId"], "0"});
  const auto reason = hear(rejected);
  ASSERT_TRUE(reason);
  EXPECT_NE(reason->text.find("noRouteError"), std::string::npos);
  EXPECT_NE(reason->text.find("deviation range"), std::string::npos);
  EXPECT_FALSE(reason->gave_up);
  EXPECT_FALSE(hear(rejected)) << "reported once";
  const Json fresh = command({0, 0}, {{2, 0}});
  EXPECT_NE(fresh["orderId"], first["orderId"]);
}

TEST_F(VdaOrdersTest, ADestinationRejectedThreeTimesInARowIsNotSentAgainUntilThePathEndsElsewhere) {
  std::optional<VdaRejection> reason;
  for (int i = 0; i < 3; ++i) {
    const Json order = command({0, 0}, {{2, 0}});
    ASSERT_FALSE(order.is_null()) << "order " << i;
    protocol::VdaMessage rejected = state();
    rejected.errors.push_back({"noRouteError", "WARNING", "no way there", order["orderId"], "0"});
    reason = hear(rejected);
    ASSERT_TRUE(reason);
    EXPECT_EQ(reason->gave_up, i == 2) << reason->text;
  }
  EXPECT_NE(reason->text.find("3 orders to (2.00, 0.00) rejected in a row"), std::string::npos)
      << reason->text;
  EXPECT_TRUE(command({0, 0}, {{2, 0}}).is_null()) << "given up on";
  EXPECT_EQ(command({0, 0}, {{0, 2}})["orderUpdateId"], 0) << "a new destination is tried";
}

TEST_F(VdaOrdersTest, AnOrderTakenEndsTheRejectionsInARow) {
  for (int i = 0; i < 2; ++i) {
    const Json order = command({0, 0}, {{2, 0}});
    protocol::VdaMessage rejected = state();
    rejected.errors.push_back({"orderError", "WARNING", "busy", order["orderId"], "0"});
    ASSERT_TRUE(hear(rejected));
  }
  const Json taken = command({0, 0}, {{2, 0}});
  hear(state(taken["orderId"], 1, true));
  // An update ending at the same place, rejected: the third rejection there, but not in a row.
  command({1.9, 0}, {{5, 0}, {2, 0}});
  protocol::VdaMessage rejected = state(taken["orderId"], 1, true);
  rejected.errors.push_back({"orderUpdateError", "WARNING", "no stitching", taken["orderId"], "1"});
  const auto reason = hear(rejected);
  ASSERT_TRUE(reason);
  EXPECT_FALSE(reason->gave_up) << reason->text;
  EXPECT_FALSE(command({1.9, 0}, {{2, 0}}).is_null());
}

TEST_F(VdaOrdersTest, AnOrderOfSomeoneElsesIsCancelledFirst) {
  hear(state("theirs", 2, true));
  const Json cancel = command({0, 0}, {{2, 0}});
  EXPECT_EQ(cancel["instantActions"][0]["actionType"], "cancelOrder");
}

}  // namespace
}  // namespace slam::gateway
