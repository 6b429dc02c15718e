// slam-simulator's flags: defaults, the configuration they build, and one-line errors naming the flag.
#include "simulator/core/sim_options.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace slam::sim {
namespace {

using ::testing::HasSubstr;

// Parses `args` as a command line; returns the CLI11 error text, empty on success.
std::string parse(SimOptions& o, std::vector<std::string> args) {
  CLI::App app{"test"};
  add_sim_options(app, o);
  std::reverse(args.begin(), args.end());  // CLI11 takes a reversed vector
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return {};
}

TEST(SimOptions, DefaultsMatchTheDocumentedOnes) {
  SimOptions o;
  ASSERT_EQ(parse(o, {}), "");
  EXPECT_EQ(o.world, "office");
  EXPECT_EQ(o.robots, 3);
  EXPECT_EQ(o.robot_protocol(), RobotProtocol::V1);
  EXPECT_EQ(o.broker, "tcp://127.0.0.1:1883");
  EXPECT_TRUE(validate(o));
  auto c = simulation_config(o);
  ASSERT_TRUE(c);
  EXPECT_DOUBLE_EQ(c->report_period, 0.1);
  EXPECT_DOUBLE_EQ(c->dt, 0.05);
  EXPECT_DOUBLE_EQ(c->odometry.drift_per_radian, OdometryConfig{}.drift_per_radian);
  EXPECT_EQ(c->odom_frame, OdomFrame::World);
}

TEST(SimOptions, FlagsReachTheConfiguration) {
  SimOptions o;
  ASSERT_EQ(parse(o, {"--protocol",   "v2",   "--rate",          "50",
                      "--noise",      "0.03", "--dropout",       "0.2",
                      "--drift",      "0.1",  "--seed",          "9",
                      "--speed",      "2",    "--random-walk",   "--mqtt-multiplex",
                      "--robots",     "500",  "--heading-drift", "0.05",
                      "--odom-frame", "start"}),
            "");
  EXPECT_EQ(o.robot_protocol(), RobotProtocol::V2);
  EXPECT_TRUE(o.mqtt_multiplex);
  SimOptions vda;
  ASSERT_EQ(parse(vda, {"--protocol", "vda5050"}), "");
  EXPECT_EQ(vda.robot_protocol(), RobotProtocol::Vda5050);
  SimOptions mixed;
  ASSERT_EQ(parse(mixed, {"--robots", "3", "--vda-robots", "1"}), "");
  EXPECT_EQ(mixed.vda_robots, 1);
  EXPECT_TRUE(validate(mixed));
  mixed.vda_robots = 4;
  EXPECT_FALSE(validate(mixed));
  auto c = simulation_config(o);
  ASSERT_TRUE(c) << c.message();
  EXPECT_DOUBLE_EQ(c->report_period, 0.02);
  EXPECT_DOUBLE_EQ(c->dt, 0.02);  // steps at least as often as reports
  EXPECT_DOUBLE_EQ(c->sensor.range_noise_sd, 0.03);
  EXPECT_DOUBLE_EQ(c->sensor.dropout, 0.2);
  EXPECT_DOUBLE_EQ(c->odometry.drift_per_metre, 0.1);
  EXPECT_DOUBLE_EQ(c->odometry.drift_per_radian, 0.05);
  EXPECT_EQ(c->odom_frame, OdomFrame::Start);
  EXPECT_EQ(c->seed, 9u);
  EXPECT_DOUBLE_EQ(c->speed_factor, 2.0);
  EXPECT_TRUE(c->random_walk);
}

TEST(SimOptions, BadValuesNameTheFlag) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--rate", "0"}, "--rate"},
      {{"--robots", "-1"}, "--robots"},
      {{"--protocol", "v3"}, "--protocol"},
      {{"--dropout", "1.5"}, "--dropout"},
      {{"--noise", "abc"}, "--noise"},
      {{"--speed", "0"}, "--speed"},
      {{"--heading-drift", "-0.1"}, "--heading-drift"},
      {{"--heading-drift", "11"}, "--heading-drift"},
      {{"--odom-frame", "map"}, "--odom-frame"},
  };
  for (const auto& [args, flag] : cases) {
    SimOptions o;
    EXPECT_THAT(parse(o, args), HasSubstr(flag));
  }
  SimOptions o;
  o.broker = "http://x";
  EXPECT_THAT(validate(o).message(), HasSubstr("--broker"));
}

TEST(SimOptions, TlsBrokerWithItsCa) {
  SimOptions o;
  ASSERT_EQ(parse(o, {"--broker", "ssl://127.0.0.1:8883", "--tls-ca-file", "ca.crt"}), "");
  EXPECT_EQ(o.tls_ca_file, "ca.crt");
  EXPECT_TRUE(validate(o));
  o.broker = "tcp://127.0.0.1:1883";  // a CA for a plain connection is a mistake, said at start
  EXPECT_THAT(validate(o).message(), HasSubstr("--tls-ca-file"));
}

TEST(SimOptions, PasswordNeedsOneConnectionPerRobot) {
  SimOptions o;
  ASSERT_EQ(parse(o, {"--mqtt-password", "s3cret"}), "");
  EXPECT_EQ(o.mqtt_password, "s3cret");
  EXPECT_TRUE(validate(o));
  o.mqtt_multiplex = true;  // one shared connection cannot log in as every robot
  EXPECT_THAT(validate(o).message(), HasSubstr("--mqtt-password"));
}

TEST(SimOptions, RecordingIsOfSimulatedRobotsOnly) {
  SimOptions o;
  ASSERT_EQ(parse(o, {"--record-log", "runs/office"}), "");
  EXPECT_EQ(o.record_log, "runs/office");
  EXPECT_TRUE(validate(o));
  o.play.logs = {"robot.clf"};  // a played log is already a log
  EXPECT_THAT(validate(o).message(), HasSubstr("--record-log"));
}

}  // namespace
}  // namespace slam::sim
