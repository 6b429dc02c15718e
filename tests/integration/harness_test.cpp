// The process-group harness itself: mosquitto and two trivial processes (one with a child of its
// own) start, are seen running, and nothing of them is left after teardown.
#include <gtest/gtest.h>
#include <signal.h>

#include <memory>
#include <vector>

#include "process_group.hpp"

namespace slam::testkit {
namespace {

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
    ASSERT_TRUE(wait_until([&] { return process_group_members(group.pid("parent")).size() == 3; }, 5s));
    EXPECT_TRUE(group.running("mosquitto"));
    EXPECT_TRUE(group.running("sleeper"));
    EXPECT_TRUE(group.running("parent"));
    pids = group.pids();
  }
  for (pid_t pid : pids) {
    EXPECT_FALSE(process_alive(pid)) << "pid " << pid << " survived teardown";
    EXPECT_TRUE(process_group_members(pid).empty()) << "children of " << pid << " survived teardown";
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

// A lease of two holds both ids: no other lease gets either.
TEST(ProcessGroupTest, ALeaseOfTwoHoldsTwoDomainsInARow) {
  DomainLease pair(2);
  std::vector<std::unique_ptr<DomainLease>> others;
  for (int i = 0; i < 20; ++i) {
    others.push_back(std::make_unique<DomainLease>());
    EXPECT_NE(others.back()->id(), pair.id());
    EXPECT_NE(others.back()->id(), pair.id() + 1);
  }
}

}  // namespace
}  // namespace slam::testkit
