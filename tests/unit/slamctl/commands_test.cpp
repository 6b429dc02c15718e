// slamctl's subcommand table: every subcommand is on the command line once, with its arguments,
// and exactly the one given is the one parsed. No participant: handlers are not run.
#include "slamctl/commands.hpp"

#include <gtest/gtest.h>

#include <set>

#include "common/core/service_options.hpp"

namespace slam::ctl {
namespace {

struct CommandLine {
  CLI::App app{"slamctl"};
  Handlers handlers = add_subcommands(app);

  // The exit code parse_command_line asks for (std::nullopt: carry on).
  std::optional<int> parse(std::vector<std::string> args) {
    args.insert(args.begin(), "slamctl");
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    return parse_command_line(app, static_cast<int>(argv.size()), argv.data());
  }

  std::vector<std::string> parsed() const {
    std::vector<std::string> names;
    for (const auto& [cli, run] : handlers)
      if (cli->parsed()) names.push_back(cli->get_name());
    return names;
  }
};

TEST(SlamctlSubcommands, NamesAreUniqueAndEachHasAHandler) {
  CommandLine line;
  std::set<std::string_view> names;
  for (const Subcommand& sub : subcommands()) {
    EXPECT_TRUE(names.insert(sub.name).second) << sub.name;
    EXPECT_FALSE(sub.help.empty()) << sub.name;
  }
  for (const char* name :
       {"status", "robots", "alerts", "forget", "mission", "missions", "record", "replay", "goal", "path",
        "map", "grid", "obstruct", "unobstruct", "reset", "pose", "sim", "echo", "store"})
    EXPECT_TRUE(names.contains(name)) << name;
  for (const auto& [cli, run] : line.handlers) EXPECT_TRUE(run) << cli->get_name();
}

TEST(SlamctlSubcommands, OnlyTheGivenSubcommandIsParsed) {
  const std::vector<std::vector<std::string>> cases = {
      {"status"},
      {"goal", "r1", "direct", "1", "2", "--size", "2"},
      {"path", "0", "0", "1", "1", "--algorithm", "rrtstar"},
      {"mission", "r1", "1", "-2", "3.5", "4", "--loop"},
      {"mission", "r1", "--file", "/tmp/patrol.yaml"},
      {"missions"},
      {"map", "save", "/tmp/m.yaml"},
      {"grid", "--resolution", "0.1", "--origin", "-5", "-5"},
      {"unobstruct", "1.5", "2"},
      {"store", "stats", "--store", "/tmp/m.db"},
      {"pose", "r1", "-1.5", "2", "-90"},
      {"sim", "spawn", "3"},
      {"echo", "slam/robot/state", "-n", "2"},
      {"status", "--json", "--verbose"},
      {"robots", "--json"},
      {"alerts", "--all", "--json"},
      {"forget", "r1"},
  };
  for (const auto& args : cases) {
    CommandLine line;
    EXPECT_EQ(line.parse(args), std::nullopt) << args[0];
    EXPECT_EQ(line.parsed(), std::vector<std::string>{args[0]});
  }
}

TEST(SlamctlSubcommands, HelpOfASubcommandExitsZero) {
  testing::internal::CaptureStdout();
  CommandLine line;
  const auto code = line.parse({"grid", "--help"});
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_EQ(code, 0);
  EXPECT_NE(out.find("--resolution"), std::string::npos) << out;
}

TEST(SlamctlSubcommands, PoseHelpNamesItsArguments) {
  testing::internal::CaptureStdout();
  CommandLine line;
  const auto code = line.parse({"pose", "--help"});
  const std::string out = testing::internal::GetCapturedStdout();
  EXPECT_EQ(code, 0);
  for (const char* word : {"robot", "theta", "degrees"}) EXPECT_NE(out.find(word), std::string::npos) << out;
}

TEST(SlamctlSubcommands, BadArgumentsExitTwoWithOneLine) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"path", "0", "0", "1"},
                                               {"sim", "spawn", "0"},
                                               {"map"},
                                               {"no-such-command"},
                                               {"pose", "r1", "1", "2"},
                                               {"pose", "r1", "nan", "2", "0"},
                                               {"pose", "r1", "1", "inf", "0"},
                                               {"pose", "r1", "1", "2", "-inf"},
                                               {"pose", "r1", "1", "2", "ninety"},
                                               {"pose", "r1", "1", "2", "3", "4"}}) {
    testing::internal::CaptureStderr();
    CommandLine line;
    const auto code = line.parse(args);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(code, 2) << testing::PrintToString(args);
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  }
}

}  // namespace
}  // namespace slam::ctl
