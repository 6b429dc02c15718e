// The run command in secure mode (compose/launch.sh --secure, what scripts/run.sh --secure runs):
// it makes its security files, the fleet explores over TLS MQTT and a DDS Security domain, and a
// participant of the secure domain with the viewer's identity sees the robots move. The viewer is
// left out (no X server needed): its binary is not in the BIN folder handed to the launcher.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "common/fastdds/fast_topics.hpp"
#include "common/fastdds/security_files.hpp"
#include "fastdds_inbox.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

namespace fs = std::filesystem;

// The last lines of a service's log, for a failure message.
std::string tail_of(const fs::path& path) {
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  constexpr size_t kTail = 3000;
  return text.size() > kTail ? text.substr(text.size() - kTail) : text;
}

TEST(SecureRun, FleetExploresOnTheSecureDomain) {
  DomainLease domain(2);  // the launcher puts the simulator on the next domain
  ProcessGroup group;
  const fs::path dir = group.dir();
  fs::create_directories(dir / "bin");
  for (const char* program : {"slam-gateway", "slam-mapper", "slam-planner", "slam-simulator", "slamctl"})
    fs::create_symlink(bin_path(program), dir / "bin" / program);
  const std::string data = (dir / "data").string();
  // The launcher runs from the source tree, as scripts/run.sh starts it.
  group.start("run",
              {"env", "-C", SLAM_SOURCE_DIR, "BIN=" + (dir / "bin").string(), "bash", "compose/launch.sh",
               "--secure", "--headless", "--robots", "2", "--domain", std::to_string(domain.id()), "--port",
               std::to_string(free_tcp_port()), "--data", data, "--logs", (dir / "logs").string()});
  ASSERT_TRUE(
      wait_until([&] { return fs::exists(dir / "data/security/identities/viewer.permissions.p7s"); }, 60s))
      << group.log("run");
  ASSERT_TRUE(wait_until([&] { return group.log("run").find("running;") != std::string::npos; }, 60s))
      << group.log("run");

  auto participant = dds::Participant::create(domain.id(), "secure-run-test",
                                              dds::SecurityFiles::in(data + "/security", "viewer"));
  ASSERT_TRUE(participant) << participant.message();
  std::mutex mutex;
  std::map<std::string, std::pair<double, double>> first;
  double moved = 0;
  size_t seen = 0;
  auto states = dds::make_reader(**participant, dds::kRobotState, [&](const RobotState& s, const auto&) {
    std::lock_guard lock(mutex);
    const auto [it, fresh] = first.try_emplace(s.robot_id().to_string(), s.pose().x(), s.pose().y());
    seen = first.size();
    moved = std::max(moved, std::hypot(s.pose().x() - it->second.first, s.pose().y() - it->second.second));
  });
  ASSERT_TRUE(states) << states.message();
  // Exploring robots leave where they were first seen; idle ones would not move at all.
  EXPECT_TRUE(wait_until(
      [&] {
        std::lock_guard lock(mutex);
        return moved > 1.0;
      },
      90s))
      << "no robot moved 1 m (" << seen << " robots seen); launcher:\n"
      << group.log("run") << "\nslamctl:\n"
      << tail_of(dir / "logs/slamctl.log") << "\nplanner:\n"
      << tail_of(dir / "logs/planner.log");
  states->reset();
  participant->reset();

  group.stop("run", SIGINT);  // the launcher stops everything it started, then exits
  EXPECT_EQ(group.wait_exit("run", 60s), 0) << group.log("run");
}

}  // namespace
}  // namespace slam::testkit
