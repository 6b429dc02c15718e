// The process-group harness itself: mosquitto and two trivial processes (one with a child of its
// own) start, are seen running, and nothing of them is left after teardown.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "process_group.hpp"

namespace slam::testkit {
namespace {

bool alive(pid_t pid) {
  return ::kill(pid, 0) == 0;
}

// Pids of every process whose process group is `pgid`, from /proc.
std::vector<pid_t> group_members(pid_t pgid) {
  std::vector<pid_t> out;
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    std::getline(stat, line);
    // Fields after the ")" closing the command name: state ppid pgrp ...
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    std::string state;
    pid_t ppid = 0, pgrp = 0;
    rest >> state >> ppid >> pgrp;
    if (pgrp == pgid && state != "Z") out.push_back(std::stoi(name));
  }
  return out;
}

TEST(ProcessGroupTest, StartsMosquittoAndProcessesAndLeavesNothingBehind) {
  DomainLease domain;
  EXPECT_GE(domain.id(), 20);
  std::vector<pid_t> pids;
  {
    ProcessGroup group;
    const int port = group.start_mosquitto();
    EXPECT_TRUE(wait_port_open(port, 1s));
    group.start("sleeper", {"sleep", "300"});
    group.start("parent", {"sh", "-c", "sleep 300 & sleep 300 & wait"});
    ASSERT_TRUE(wait_until([&] { return group_members(group.pid("parent")).size() == 3; }, 5s));
    EXPECT_TRUE(group.running("mosquitto"));
    EXPECT_TRUE(group.running("sleeper"));
    EXPECT_TRUE(group.running("parent"));
    pids = group.pids();
  }
  for (pid_t pid : pids) {
    EXPECT_FALSE(alive(pid)) << "pid " << pid << " survived teardown";
    EXPECT_TRUE(group_members(pid).empty()) << "children of " << pid << " survived teardown";
  }
}

TEST(ProcessGroupTest, ReportsExitCodesAndLogs) {
  ProcessGroup group;
  group.start("fails", {"sh", "-c", "echo bad flag >&2; exit 3"});
  EXPECT_EQ(group.wait_exit("fails", 5s), 3);
  EXPECT_NE(group.log("fails").find("bad flag"), std::string::npos);
}

TEST(ProcessGroupTest, DomainLeasesAreExclusive) {
  DomainLease a;
  DomainLease b;
  EXPECT_NE(a.id(), b.id());
}

}  // namespace
}  // namespace slam::testkit
