#include "bridge/core/bridge_options.hpp"

#include <gtest/gtest.h>

namespace slam::bridge {
namespace {

TEST(BridgeOptions, ParsesAddressAndPort) {
  auto bind = parse_bind("0.0.0.0:9000");
  ASSERT_TRUE(bind) << bind.message();
  EXPECT_EQ(bind->host, "0.0.0.0");
  EXPECT_EQ(bind->port, 9000);
}

TEST(BridgeOptions, RefusesABindWithoutAValidPort) {
  for (const char* text : {"8765", ":8765", "localhost:", "localhost:0", "localhost:70000", "localhost:87a"})
    EXPECT_FALSE(parse_bind(text)) << text;
}

TEST(BridgeOptions, DefaultsAreValidAndABadPeriodIsNamed) {
  BridgeOptions o;
  EXPECT_TRUE(validate(o));
  EXPECT_EQ(o.bind, "127.0.0.1:8765");
  o.periods.map_full_s = 0.0;
  const Status s = validate(o);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("periods-map-full-s"), std::string::npos) << s.message();
}

TEST(BridgeOptions, TheRosFaceIsOnUnlessTurnedOffAndNamesItsRobot) {
  BridgeOptions defaults;
  EXPECT_TRUE(defaults.ros);
  EXPECT_TRUE(defaults.ros_robot.empty());
  CLI::App app;
  BridgeOptions o;
  add_bridge_options(app, o);
  app.parse("--no-ros --ros-robot r1", false);
  EXPECT_FALSE(o.ros);
  EXPECT_EQ(o.ros_robot, "r1");
  EXPECT_TRUE(validate(o));
  o.ros_robot = std::string(65, 'r');
  EXPECT_FALSE(validate(o));
}

}  // namespace
}  // namespace slam::bridge
