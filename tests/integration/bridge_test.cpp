// The bridge against a client no one here wrote: Foxglove's own FoxgloveClient (Node,
// @foxglove/ws-protocol, pinned in tests/node/package-lock.json) connects to the bridge of a running
// fleet (mosquitto, gateway, mapper, planner, one simulated robot in the empty world), lists and
// subscribes to every channel, checks every message against @foxglove/schemas' JSON schemas, calls
// the path service and publishes a goal that must move the robot (tests/node/foxglove_client_test.mjs).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "process_group.hpp"

namespace slam {
namespace {

using namespace std::chrono_literals;

bool node_installed() {
  return std::system("node --version > /dev/null 2>&1") == 0;
}

TEST(BridgeTest, FoxgloveClientSeesTheFleetAndDrivesARobot) {
  if (!node_installed())
    GTEST_SKIP() << "node is not installed (apt-get install nodejs): no Foxglove client to run";
  const std::string node_dir = SLAM_NODE_TESTS_DIR;
  ASSERT_TRUE(std::filesystem::exists(node_dir + "/node_modules/@foxglove/ws-protocol"))
      << "the pinned npm packages are missing: run scripts/setup.sh (npm ci in tests/node)";

  testkit::DomainLease lease;
  testkit::ProcessGroup group;
  const std::string domain = std::to_string(lease.id());
  const int mqtt_port = group.start_mosquitto();
  const std::string broker = "tcp://127.0.0.1:" + std::to_string(mqtt_port);
  const int ws_port = testkit::free_tcp_port();
  group.start("bridge", {testkit::bin_path("slam-bridge"), "--domain", domain, "--bind",
                         "127.0.0.1:" + std::to_string(ws_port)});
  group.start("gateway", {testkit::bin_path("slam-gateway"), "--domain", domain, "--broker", broker});
  group.start("mapper", {testkit::bin_path("slam-mapper"), "--domain", domain, "--store",
                         group.dir() + "/map.db", "--snapshot-period", "1"});
  group.start("planner", {testkit::bin_path("slam-planner"), "--domain", domain, "--goal-store",
                          group.dir() + "/goals.json"});
  group.start("simulator", {testkit::bin_path("slam-simulator"), "--domain", domain, "--broker", broker,
                            "--world", "empty", "--robots", "1", "--drift", "0", "--seed", "5"});
  ASSERT_TRUE(testkit::wait_port_open(ws_port, 20s)) << group.log("bridge");

  group.start("client", {"node", node_dir + "/foxglove_client_test.mjs",
                         "ws://127.0.0.1:" + std::to_string(ws_port), "90"});
  const int code = group.wait_exit("client", 120s);
  EXPECT_EQ(code, 0) << group.log("client");
  EXPECT_TRUE(group.running("bridge")) << group.log("bridge");
}

}  // namespace
}  // namespace slam
