// The fleet across three hosts: network namespaces joined by a bridge stand for hosts A (mosquitto,
// gateway), B (mapper, planner, Fast DDS discovery server) and C (simulator, slamctl, headless
// viewer), with no multicast between them. The Fast DDS programs are clients of the discovery
// server (ROS_DISCOVERY_SERVER); the Cyclone simulator uses static unicast peers
// (compose/dds/cyclonedds-unicast.xml) and is read by a slamctl on its own host that uses simple
// discovery: Fast DDS 2.9 keeps discovery-server participants and simple ones apart
// (docs/deployment.md, section 3). The fleet must explore, keep going while the discovery server is
// killed, be found again once it is back, and resume after host B's services are killed and
// restarted. Needs root (namespaces); skipped otherwise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "process_group.hpp"

namespace slam {
namespace {

using namespace testkit;

constexpr int kRobots = 3;
constexpr int kDiscoveryPort = 11811;
constexpr int kBrokerPort = 1883;  // each host has its own network stack: no collision with other tests

bool shell_ok(const std::string& command) {
  return std::system((command + " >/dev/null 2>&1").c_str()) == 0;
}

// Hosts a, b and c (10.77.0.1 .. 3): a network namespace each, joined by a bridge in a fourth one.
// Interface names live inside the namespaces, so parallel runs differ only in the namespace names,
// which end in this process's id. The destructor removes them; the constructor first removes those
// of earlier runs whose process is gone (a test killed before its destructor ran).
class Hosts {
 public:
  Hosts() : suffix_("-mh" + std::to_string(::getpid())) {
    remove_stale();
    const std::string sw = "sw" + suffix_;
    run("ip netns add " + sw);
    run("ip -n " + sw + " link add br0 type bridge");
    run("ip -n " + sw + " link set br0 up");
    for (const char host : std::string("abc")) {
      const std::string ns = name(host), port = std::string("p") + host;
      run("ip netns add " + ns);
      run("ip -n " + sw + " link add " + port + " type veth peer name eth0 netns " + ns);
      run("ip -n " + sw + " link set " + port + " master br0 up");
      run("ip -n " + ns + " addr add " + address(host) + "/24 dev eth0");
      run("ip -n " + ns + " link set eth0 up");
      run("ip -n " + ns + " link set lo up");
    }
  }
  ~Hosts() {
    for (const std::string prefix : {"a", "b", "c", "sw"}) shell_ok("ip netns del " + prefix + suffix_);
  }
  Hosts(const Hosts&) = delete;
  Hosts& operator=(const Hosts&) = delete;

  std::string name(char host) const { return std::string(1, host) + suffix_; }
  static std::string address(char host) { return "10.77.0." + std::to_string(host - 'a' + 1); }

  // argv running `argv` on `host` with only the DDS discovery settings in `env` (ip netns exec and
  // env both exec: the pid is the program's, and the parent-death signal stays set).
  std::vector<std::string> on(char host, const std::vector<std::string>& env,
                              const std::vector<std::string>& argv) const {
    std::vector<std::string> out{"ip",
                                 "netns",
                                 "exec",
                                 name(host),
                                 "env",
                                 "-u",
                                 "ROS_DISCOVERY_SERVER",
                                 "-u",
                                 "FASTRTPS_DEFAULT_PROFILES_FILE",
                                 "-u",
                                 "CYCLONEDDS_URI"};
    out.insert(out.end(), env.begin(), env.end());
    out.insert(out.end(), argv.begin(), argv.end());
    return out;
  }

 private:
  static void run(const std::string& command) {
    if (!shell_ok(command)) throw std::runtime_error("failed: " + command);
  }
  static void remove_stale() {
    const std::regex ours("^(a|b|c|sw)-mh([0-9]+)$");
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator("/run/netns", ec)) {
      const std::string file = e.path().filename();
      std::smatch m;
      if (std::regex_match(file, m, ours) && !process_alive(std::stoi(m[2].str())))
        shell_ok("ip netns del " + file);
    }
  }

  std::string suffix_;
};

// One service of `slamctl status --json` and its counters.
struct ServiceStatus {
  std::string service;
  long pid = 0;
  std::map<std::string, int64_t> counters;
  int64_t counter(const std::string& name) const {
    const auto it = counters.find(name);
    return it == counters.end() ? -1 : it->second;
  }
};

// Nothing parsed from output that is not JSON (slamctl failed: its error line).
std::vector<ServiceStatus> parse_status(const std::string& out) {
  std::vector<ServiceStatus> services;
  const auto json = nlohmann::json::parse(out, nullptr, false);
  if (!json.is_array()) return services;
  for (const auto& s : json) {
    ServiceStatus status;
    status.service = s.value("service", "");
    status.pid = s.value("pid", 0L);
    for (const auto& [name, value] : s["counters"].items()) status.counters[name] = value.get<int64_t>();
    services.push_back(std::move(status));
  }
  return services;
}

class Fleet {
 public:
  Fleet(const Hosts& hosts, ProcessGroup& group, int domain)
      : hosts_(hosts), group_(group), domain_(domain) {}

  // The environment of a discovery-server client.
  std::vector<std::string> client_env() const {
    return {"ROS_DISCOVERY_SERVER=" + Hosts::address('b') + ":" + std::to_string(kDiscoveryPort)};
  }

  void start_discovery_server() {
    group_.start("discovery", hosts_.on('b', {},
                                        {"fast-discovery-server", "-i", "0", "-l", Hosts::address('b'), "-p",
                                         std::to_string(kDiscoveryPort), "-x",
                                         SLAM_SOURCE_DIR "/compose/dds/fastdds-discovery-server.xml"}));
  }
  void start_host_b_services() {
    group_.start("mapper", hosts_.on('b', client_env(),
                                     {bin_path("slam-mapper"), "--domain", std::to_string(domain_), "--store",
                                      group_.dir() + "/map.db", "--snapshot-period", "1"}));
    group_.start("planner", hosts_.on('b', client_env(),
                                      {bin_path("slam-planner"), "--domain", std::to_string(domain_),
                                       "--goal-store", group_.dir() + "/goals.json"}));
  }

  // `slamctl ARGS` on host C, as a discovery-server client (`ds`) or with simple discovery; its
  // exit code (-1 when it hung) and output.
  std::pair<int, std::string> slamctl(bool ds, const std::vector<std::string>& args) {
    std::vector<std::string> argv{bin_path("slamctl"), "--domain", std::to_string(domain_), "--timeout", "5"};
    argv.insert(argv.end(), args.begin(), args.end());
    const std::string name = "slamctl-" + std::to_string(++runs_);
    group_.start(name, hosts_.on('c', ds ? client_env() : std::vector<std::string>{}, argv));
    const int rc = group_.wait_exit(name, 60s);
    if (rc == -1) group_.stop(name, SIGKILL);
    return {rc, group_.log(name)};
  }
  std::vector<ServiceStatus> status(bool ds) {
    return parse_status(slamctl(ds, {"status", "--json"}).second);
  }

  // Polls `slamctl status` until `pred` holds for what it shows.
  bool wait_status(bool ds, const std::function<bool(const std::vector<ServiceStatus>&)>& pred,
                   std::chrono::seconds timeout) {
    return wait_until([&] { return pred(status(ds)); }, timeout, 1s);
  }

 private:
  const Hosts& hosts_;
  ProcessGroup& group_;
  int domain_;
  int runs_ = 0;
};

// The status line of `service` from process `pid` (any process when 0).
std::optional<ServiceStatus> find(const std::vector<ServiceStatus>& all, const std::string& service,
                                  long pid = 0) {
  for (const ServiceStatus& s : all)
    if (s.service == service && (pid == 0 || s.pid == pid)) return s;
  return std::nullopt;
}

TEST(Multihost, FleetExploresAcrossHostsAndSurvivesDiscoveryServerAndServiceRestarts) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to create network namespaces";
  if (!shell_ok("ip netns list")) GTEST_SKIP() << "`ip netns` is not available";

  DomainLease lease;
  Hosts hosts;  // declared before the group: every process is gone before the namespaces are removed
  ProcessGroup group;
  Fleet fleet(hosts, group, lease.id());
  const std::string domain = std::to_string(lease.id());
  const std::string broker = "tcp://" + Hosts::address('a') + ":" + std::to_string(kBrokerPort);

  // Host B: the discovery server first, so the services find it at once.
  fleet.start_discovery_server();
  // Host A: the broker, reachable from the other hosts, and the gateway.
  const std::string conf = group.write_mosquitto_config("mosquitto", kBrokerPort, Hosts::address('a'));
  group.start("mosquitto", hosts.on('a', {}, {"mosquitto", "-c", conf}));
  ASSERT_TRUE(wait_until([&] { return group.log("mosquitto").find(" running") != std::string::npos; }, 10s))
      << "mosquitto did not start";
  group.start("gateway", hosts.on('a', fleet.client_env(),
                                  {bin_path("slam-gateway"), "--domain", domain, "--broker", broker}));
  fleet.start_host_b_services();
  // Host C: the simulator with the committed unicast profile (its peer: this host's tools).
  group.start("simulator",
              hosts.on('c', {"CYCLONEDDS_URI=file://" SLAM_SOURCE_DIR "/compose/dds/cyclonedds-unicast.xml"},
                       {bin_path("slam-simulator"), "--domain", domain, "--broker", broker, "--world",
                        "office", "--robots", std::to_string(kRobots), "--seed", "7"}));

  const auto all_services = [](const std::vector<ServiceStatus>& s) {
    return find(s, "gateway") && find(s, "mapper") && find(s, "planner");
  };
  ASSERT_TRUE(fleet.wait_status(true, all_services, 120s))
      << "slamctl on host C never saw the gateway (A), mapper and planner (B) through the discovery server";
  ASSERT_TRUE(fleet.wait_status(
      false, [](const auto& s) { return find(s, "simulator").has_value(); }, 60s))
      << "slamctl on host C never saw the Cyclone simulator through its unicast peer";

  const auto [goal_rc, goal_out] = fleet.slamctl(true, {"goal", "all", "explore"});
  ASSERT_EQ(goal_rc, 0) << goal_out;

  // The fleet explores: observations from C through the broker on A reach the mapper on B, the
  // planner on B sends waypoints that reach the robots on C through the gateway and the broker.
  int64_t cells = 0, waypoints = 0;
  ASSERT_TRUE(fleet.wait_status(
      true,
      [&](const auto& s) {
        const auto mapper = find(s, "mapper");
        const auto planner = find(s, "planner");
        if (!mapper || !planner) return false;
        cells = mapper->counter("cells_changed");
        waypoints = planner->counter("waypoints_sent");
        return cells > 0 && waypoints > 0;
      },
      120s))
      << "the map does not grow or the planner sends no waypoints";
  int64_t received = 0;
  ASSERT_TRUE(fleet.wait_status(
      false,
      [&](const auto& s) {
        const auto sim = find(s, "simulator");
        received = sim ? sim->counter("waypoints_received") : -1;
        return received > 0;
      },
      120s))
      << "the simulated robots receive no waypoints";

  // A headless viewer on host C gets the map from B and the robots' points from A.
  if (::access("/usr/bin/xvfb-run", X_OK) == 0) {
    const std::string png = group.dir() + "/viewer.png";
    group.start("viewer",
                hosts.on('c', fleet.client_env(),
                         {"xvfb-run", "-a", "-s", "-screen 0 640x480x24", bin_path("slam-viewer"), "--domain",
                          domain, "--width", "640", "--height", "480", "--screenshot", png, "--frames", "5",
                          "--wait-map", "--wait-robots", std::to_string(kRobots)}));
    EXPECT_EQ(group.wait_exit("viewer", 120s), 0) << "the viewer never showed the map and every robot";
    EXPECT_TRUE(std::filesystem::exists(png));
  } else {
    std::printf("multihost_test: xvfb-run is not installed; the viewer is not run\n");
  }

  // The discovery server dies: matched services keep talking (robots still get waypoints).
  group.stop("discovery", SIGKILL);
  const int64_t received_before = received;
  EXPECT_TRUE(fleet.wait_status(
      false,
      [&](const auto& s) {
        const auto sim = find(s, "simulator");
        return sim && sim->counter("waypoints_received") > received_before;
      },
      60s))
      << "waypoints stopped while the discovery server was down";

  // It comes back (same id, so the same GUID prefix): a new slamctl sees every service again, with
  // counters that kept moving.
  fleet.start_discovery_server();
  const int64_t cells_before = cells, waypoints_before = waypoints;
  EXPECT_TRUE(fleet.wait_status(
      true,
      [&](const auto& s) {
        const auto mapper = find(s, "mapper");
        const auto planner = find(s, "planner");
        return find(s, "gateway") && mapper && planner && mapper->counter("cells_changed") > cells_before &&
               planner->counter("waypoints_sent") > waypoints_before;
      },
      180s))
      << "after the discovery server restarted, a new slamctl does not see every service";

  // Host B's services die and come back: the new mapper and planner are found and exploration resumes.
  group.stop("mapper", SIGKILL);
  group.stop("planner", SIGKILL);
  fleet.start_host_b_services();
  const long mapper_pid = group.pid("mapper"), planner_pid = group.pid("planner");
  EXPECT_TRUE(fleet.wait_status(
      true,
      [&](const auto& s) {
        const auto mapper = find(s, "mapper", mapper_pid);
        const auto planner = find(s, "planner", planner_pid);
        return mapper && planner && mapper->counter("observations") > 0 &&
               planner->counter("waypoints_sent") > 0;
      },
      180s))
      << "the restarted mapper and planner on host B do not map and plan";
  int64_t received_restart = -1;
  ASSERT_TRUE(fleet.wait_status(
      false,
      [&](const auto& s) {
        const auto now = find(s, "simulator");
        received_restart = now ? now->counter("waypoints_received") : -1;
        return received_restart >= 0;
      },
      60s))
      << "slamctl on host C lost the simulator";
  EXPECT_TRUE(fleet.wait_status(
      false,
      [&](const auto& s) {
        const auto now = find(s, "simulator");
        return now && now->counter("waypoints_received") > received_restart;
      },
      60s))
      << "the robots receive no waypoints from the restarted planner";
  for (const char* name : {"gateway", "mapper", "planner", "simulator", "mosquitto", "discovery"})
    EXPECT_TRUE(group.running(name)) << name << " exited";
}

}  // namespace
}  // namespace slam
