// The log player's flags: defaults, robot ids from file names or given, and one-line errors.
#include "simulator/core/play_options.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "simulator/core/sim_options.hpp"

namespace slam::sim {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string parse(SimOptions& o, std::vector<std::string> args) {
  CLI::App app{"test"};
  add_sim_options(app, o);
  std::reverse(args.begin(), args.end());
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return {};
}

TEST(PlayOptions, OffByDefault) {
  SimOptions o;
  ASSERT_EQ(parse(o, {}), "");
  EXPECT_FALSE(o.play.enabled());
  EXPECT_DOUBLE_EQ(o.play.rate, 1.0);
  EXPECT_EQ(o.play.pieces, 1);
  EXPECT_TRUE(validate(o));
}

TEST(PlayOptions, FlagsReachTheStruct) {
  SimOptions o;
  ASSERT_EQ(parse(o, {"--play",
                      "a.clf",
                      "--play",
                      "b.mcap",
                      "--play-robot-id",
                      "r1",
                      "--play-robot-id",
                      "r2",
                      "--play-rate",
                      "0",
                      "--play-beams",
                      "32",
                      "--play-max-range",
                      "12",
                      "--play-start",
                      "5",
                      "--play-end",
                      "60",
                      "--play-pieces",
                      "4",
                      "--play-scan-topic",
                      "/scan",
                      "--play-odom-topic",
                      "/odom"}),
            "");
  EXPECT_THAT(o.play.logs, ElementsAre("a.clf", "b.mcap"));
  EXPECT_DOUBLE_EQ(o.play.rate, 0);
  EXPECT_EQ(o.play.beams, 32);
  EXPECT_DOUBLE_EQ(o.play.max_range_m, 12);
  EXPECT_DOUBLE_EQ(o.play.end_s, 60);
  EXPECT_EQ(o.play.pieces, 4);
  EXPECT_EQ(o.play.scan_topic, "/scan");
  ASSERT_TRUE(validate(o)) << validate(o).message();
  EXPECT_THAT(*play_robot_ids(o.play), ElementsAre("r1", "r2"));
}

TEST(PlayOptions, RobotIdsFromFileNames) {
  EXPECT_EQ(robot_id_from_path("/data/intel.clf.gz"), "intel");
  EXPECT_EQ(robot_id_from_path("run 2/fr079.log"), "fr079");
  EXPECT_EQ(robot_id_from_path("bags/hall+way#1.mcap"), "hall_way_1");
  EXPECT_EQ(robot_id_from_path(".gz"), ".gz");
  EXPECT_EQ(robot_id_from_path("/"), "log");
  EXPECT_EQ(robot_id_from_path(std::string(100, 'x') + ".clf").size(), 56u);
  PlayOptions o;
  o.logs = {"x/intel.clf.gz", "y/aces.clf"};
  EXPECT_THAT(*play_robot_ids(o), ElementsAre("intel", "aces"));
}

TEST(PlayOptions, BadCombinationsNameTheFlag) {
  PlayOptions o;
  o.logs = {"a/robot.clf", "b/robot.clf"};
  EXPECT_THAT(validate(o).message(), HasSubstr("two --play logs would play as robot 'robot'"));
  o.robot_ids = {"one"};
  EXPECT_THAT(validate(o).message(), HasSubstr("--play-robot-id is given 1 times for 2 --play logs"));
  o.robot_ids = {"one", "t/wo"};
  EXPECT_THAT(validate(o).message(), HasSubstr("'t/wo' is not a valid robot id"));
  o.robot_ids = {"one", std::string(63, 'x')};
  o.pieces = 2;  // "-2" makes it 65 bytes
  EXPECT_THAT(validate(o).message(), HasSubstr("not a valid robot id"));
  o = PlayOptions{};
  o.logs = {"a.clf"};
  o.start_s = 10;
  o.end_s = 5;
  EXPECT_THAT(validate(o).message(), HasSubstr("--play-end 5 is not after --play-start 10"));
  PlayOptions ids_only;
  ids_only.robot_ids = {"r"};
  EXPECT_THAT(validate(ids_only).message(), HasSubstr("needs --play"));
  SimOptions sim;
  EXPECT_NE(parse(sim, {"--play-rate", "-1"}), "");
  EXPECT_NE(parse(sim, {"--play-pieces", "0"}), "");
}

}  // namespace
}  // namespace slam::sim
