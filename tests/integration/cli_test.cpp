// Every program answers --help with exit 0, and a bad flag with exit 2 and one line on stderr.
#include <gtest/gtest.h>

#include "process_group.hpp"

namespace slam::testkit {
namespace {

class CliTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CliTest, HelpExitsZeroAndNamesTheProgram) {
  ProcessGroup group;
  group.start("help", {bin_path(GetParam()), "--help"});
  EXPECT_EQ(group.wait_exit("help", 20s), 0);
  EXPECT_NE(group.log("help").find("--domain"), std::string::npos) << group.log("help");
}

TEST_P(CliTest, BadFlagExitsTwoWithOneLine) {
  ProcessGroup group;
  // "status" satisfies slamctl's required subcommand; for the services it is one more bad argument.
  group.start("bad", {bin_path(GetParam()), "--no-such-flag", "status"});
  EXPECT_EQ(group.wait_exit("bad", 20s), 2);
  const std::string log = group.log("bad");
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << log;
  EXPECT_NE(log.find("--no-such-flag"), std::string::npos) << log;
}

TEST_P(CliTest, BadDomainExitsTwo) {
  ProcessGroup group;
  group.start("bad", {bin_path(GetParam()), "--domain", "999"});
  EXPECT_EQ(group.wait_exit("bad", 20s), 2);
}

INSTANTIATE_TEST_SUITE_P(Programs, CliTest,
                         ::testing::Values("slam-gateway", "slam-mapper", "slam-planner", "slam-simulator",
                                           "slam-viewer", "slamctl"),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                           std::string name = p.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace slam::testkit
