// A crashed test leaves nothing behind: a test process that started mosquitto and a service is
// killed with SIGKILL (no destructor runs), and every process it started must go with it.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "process_group.hpp"
#include "temp_dir.hpp"

namespace slam::testkit {
namespace {

// "<name> <pid>" lines of the child's pid file.
std::map<std::string, pid_t> read_pids(const std::filesystem::path& file) {
  std::map<std::string, pid_t> out;
  std::ifstream in(file);
  std::string name;
  pid_t pid = 0;
  while (in >> name >> pid) out[name] = pid;
  return out;
}

// Fast DDS files in /dev/shm (shared-memory transport, data sharing).
std::set<std::string> fastdds_shm_files() {
  std::set<std::string> out;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/dev/shm", ec)) {
    const std::string name = e.path().filename();
    if (name.starts_with("fastrtps") || name.starts_with("fast_datasharing") ||
        name.starts_with("sem.fastrtps"))
      out.insert(name);
  }
  return out;
}

TEST(CrashCleanupTest, ProcessesOfAKilledTestDieWithIt) {
  DomainLease domain;
  TempDir dir("crash-cleanup");
  const auto pid_file = dir / "pids";
  const auto shm_before = fastdds_shm_files();
  ProcessGroup group;
  group.start("child",
              {bin_path("testkit_process_group_child"), std::to_string(domain.id()), pid_file.string()});
  ASSERT_TRUE(wait_until([&] { return std::filesystem::exists(pid_file) || !group.running("child"); }, 20s))
      << group.log("child");
  const auto pids = read_pids(pid_file);
  ASSERT_EQ(pids.size(), 2u) << group.log("child");
  for (const auto& [name, pid] : pids) ASSERT_TRUE(process_alive(pid)) << name << " is not running";

  group.stop("child", SIGKILL);

  for (const auto& [name, pid] : pids) {
    EXPECT_TRUE(wait_until([&] { return process_group_members(pid).empty(); }, 5s))
        << name << " (pid " << pid << ") or a process of its group outlived the killed test";
  }
  for (const auto& [name, pid] : pids) ::kill(-pid, SIGKILL);  // leave nothing even when the test failed
  std::set<std::string> left;
  for (const auto& file : fastdds_shm_files())
    if (!shm_before.contains(file)) left.insert(file);
  EXPECT_TRUE(left.empty()) << "Fast DDS left " << left.size() << " files in /dev/shm, e.g. "
                            << *left.begin();
}

}  // namespace
}  // namespace slam::testkit
