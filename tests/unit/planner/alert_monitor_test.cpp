// AlertMonitor: which facts raise and clear which alerts, and that only the owner speaks.
#include "planner/core/alert_monitor.hpp"

#include <gtest/gtest.h>

#include <set>

namespace slam::planner {
namespace {

constexpr int64_t kSecond = 1'000'000'000;

struct Owner {
  std::set<std::string> not_mine;  // keys another planner owns
  bool operator()(const std::string& key) const { return !not_mine.contains(key); }
};

std::vector<AlertChange> run(AlertMonitor& m, int64_t now_s, const Owner& owner = {}) {
  return m.evaluate(now_s * kSecond, 1000 * kSecond + now_s * kSecond, owner);
}

TEST(AlertMonitor, OfflineRobotRaisesOnceAndClearsWhenBackOnline) {
  AlertMonitor m;
  m.robot("r1", true, -1.0f);
  EXPECT_TRUE(run(m, 1).empty());
  m.robot("r1", false, -1.0f);
  const auto raised = run(m, 2);
  ASSERT_EQ(raised.size(), 1u);
  EXPECT_EQ(raised[0].change, AlertChange::Kind::Raised);
  EXPECT_EQ(raised[0].alert_id, "offline/r1");
  EXPECT_EQ(raised[0].kind, AlertKind::RobotOffline);
  EXPECT_EQ(raised[0].subject, "r1");
  EXPECT_EQ(raised[0].raised_ns, 1002 * kSecond);
  EXPECT_FALSE(raised[0].send_home);
  EXPECT_TRUE(run(m, 3).empty()) << "an active alert is not raised again";
  EXPECT_EQ(m.active().size(), 1u);
  m.robot("r1", true, -1.0f);
  const auto cleared = run(m, 4);
  ASSERT_EQ(cleared.size(), 1u);
  EXPECT_EQ(cleared[0].change, AlertChange::Kind::Cleared);
  EXPECT_EQ(cleared[0].raised_ns, 1002 * kSecond) << "a cleared alert keeps when it was raised";
  EXPECT_TRUE(m.active().empty());
}

TEST(AlertMonitor, ALostRobotRaisesUntilItIsFoundAgain) {
  AlertMonitor m;
  m.robot_lost("r1", false);
  EXPECT_TRUE(run(m, 1).empty());
  m.robot_lost("r1", true);
  const auto raised = run(m, 2);
  ASSERT_EQ(raised.size(), 1u);
  EXPECT_EQ(raised[0].alert_id, "lost/r1");
  EXPECT_EQ(raised[0].kind, AlertKind::RobotLost);
  EXPECT_FALSE(raised[0].send_home);  // it cannot be sent anywhere: where it is is unknown
  m.robot_lost("r1", false);
  const auto cleared = run(m, 3);
  ASSERT_EQ(cleared.size(), 1u);
  EXPECT_EQ(cleared[0].change, AlertChange::Kind::Cleared);
}

TEST(AlertMonitor, LowBatterySendsHomeOnceWithHysteresis) {
  AlertConfig c;
  c.battery_low = 0.2;
  c.battery_clear_margin = 0.05;
  AlertMonitor m(c);
  m.robot("r1", true, 0.5f);
  EXPECT_TRUE(run(m, 1).empty());
  m.robot("r1", true, 0.15f);
  const auto raised = run(m, 2);
  ASSERT_EQ(raised.size(), 1u);
  EXPECT_EQ(raised[0].alert_id, "battery/r1");
  EXPECT_EQ(raised[0].kind, AlertKind::BatteryLow);
  EXPECT_TRUE(raised[0].send_home);
  EXPECT_NE(raised[0].message.find("15 %"), std::string::npos) << raised[0].message;
  m.robot("r1", true, 0.22f);  // above the level, within the margin: still low
  EXPECT_TRUE(run(m, 3).empty());
  m.robot("r1", true, 0.18f);
  EXPECT_TRUE(run(m, 4).empty()) << "no second trip home while the alert stands";
  m.robot("r1", false, -1.0f);  // the last will carries no battery: still low
  const auto offline = run(m, 5);
  ASSERT_EQ(offline.size(), 1u);
  EXPECT_EQ(offline[0].alert_id, "offline/r1");
  m.robot("r1", true, 0.26f);
  const auto cleared = run(m, 6);
  ASSERT_EQ(cleared.size(), 2u) << "offline and battery";
  for (const auto& change : cleared) {
    EXPECT_EQ(change.change, AlertChange::Kind::Cleared) << change.alert_id;
    EXPECT_FALSE(change.send_home) << change.alert_id;
  }
}

TEST(AlertMonitor, UnknownBatteryAndZeroLevelRaiseNothing) {
  AlertMonitor m;
  m.robot("v1-robot", true, -1.0f);
  EXPECT_TRUE(run(m, 1).empty());
  AlertConfig off;
  off.battery_low = 0.0;
  AlertMonitor disabled(off);
  disabled.robot("r1", true, 0.01f);
  EXPECT_TRUE(run(disabled, 1).empty());
}

TEST(AlertMonitor, SilentServiceRaisesAfterTheSilenceAndClearsWhenHeardAgain) {
  AlertConfig c;
  c.service_silent_s = 5.0;
  c.service_forget_s = 60.0;
  AlertMonitor m(c);
  m.heartbeat("gateway", "host:1", false, 10 * kSecond);
  EXPECT_TRUE(run(m, 14).empty());
  const auto raised = run(m, 15);
  ASSERT_EQ(raised.size(), 1u);
  EXPECT_EQ(raised[0].alert_id, "silent/gateway/host:1");
  EXPECT_EQ(raised[0].kind, AlertKind::ServiceSilent);
  EXPECT_EQ(raised[0].subject, "gateway/host:1");
  m.heartbeat("gateway", "host:1", false, 16 * kSecond);
  const auto cleared = run(m, 16);
  ASSERT_EQ(cleared.size(), 1u);
  EXPECT_EQ(cleared[0].change, AlertChange::Kind::Cleared);
}

TEST(AlertMonitor, ServiceThatSaysItStopsLeavesWithoutAlert) {
  AlertMonitor m;
  m.heartbeat("mapper", "host:2", false, 0);
  m.heartbeat("mapper", "host:2", true, kSecond);
  EXPECT_TRUE(run(m, 100).empty());
}

TEST(AlertMonitor, SilentServiceIsForgottenAfterTheForgetTime) {
  AlertConfig c;
  c.service_silent_s = 5.0;
  c.service_forget_s = 60.0;
  AlertMonitor m(c);
  m.heartbeat("gateway", "host:1", false, 0);
  ASSERT_EQ(run(m, 10).size(), 1u);
  const auto forgotten = run(m, 60);
  ASSERT_EQ(forgotten.size(), 1u);
  EXPECT_EQ(forgotten[0].change, AlertChange::Kind::Cleared);
  EXPECT_TRUE(run(m, 61).empty());
}

TEST(AlertMonitor, ForgottenRobotClearsItsAlerts) {
  AlertMonitor m;
  m.robot("r1", false, 0.05f);
  ASSERT_EQ(run(m, 1).size(), 2u);
  m.forget_robot("r1");
  const auto cleared = run(m, 2);
  ASSERT_EQ(cleared.size(), 2u);
  for (const auto& c : cleared) EXPECT_EQ(c.change, AlertChange::Kind::Cleared);
  EXPECT_TRUE(m.active().empty());
}

TEST(AlertMonitor, OnlyTheOwnerRaisesAndAMovedSubjectIsReleased) {
  AlertMonitor m;
  m.robot("r1", false, -1.0f);
  m.heartbeat("viewer", "host:3", false, 0);
  Owner other;
  other.not_mine = {"r1", AlertMonitor::ownership_key(AlertKind::ServiceSilent, "viewer/host:3")};
  EXPECT_TRUE(run(m, 10, other).empty()) << "another planner owns both subjects";

  const auto raised = run(m, 11);
  ASSERT_EQ(raised.size(), 2u);
  const auto moved = run(m, 12, other);
  ASSERT_EQ(moved.size(), 2u);
  for (const auto& c : moved) EXPECT_EQ(c.change, AlertChange::Kind::Released);
  EXPECT_TRUE(m.active().empty());
}

TEST(AlertMonitor, ValidatesItsConfiguration) {
  EXPECT_TRUE(validate(AlertConfig{}));
  AlertConfig c;
  c.battery_low = 1.5;
  EXPECT_FALSE(validate(c));
  c = {};
  c.service_silent_s = 0.1;
  EXPECT_FALSE(validate(c));
  c = {};
  c.service_forget_s = c.service_silent_s;
  EXPECT_FALSE(validate(c));
}

}  // namespace
}  // namespace slam::planner
