// DDS Security with the files of compose/make-security.sh: a real slam-gateway joins a secure domain
// as identity "gateway" and turns a robot's MQTT messages into observations. The test's participants
// show that a participant without a certificate discovers and receives nothing, that an identity
// without the permission for a topic cannot write it (slamctl run as the mapper sends no goal), and
// that no robot id or coordinate crosses the wire in clear (every UDP packet captured during the run;
// the same run on a plain domain, where they are in clear, shows the capture sees them).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <linux/if_ether.h>
#include <netinet/ip.h>
#include <netpacket/packet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "common/fastdds/security_files.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

// A robot and the v1 adv it sends: its position as int16 LE centimetres; the observation carries
// the doubles. The secure and the plain wire tests use different ones: ctest may run them at once,
// and each capture sees the other's packets.
struct Report {
  std::string robot;
  std::string adv;
  double x, y;
};
// Values no other test on the machine sends (the capture sees every process's UDP).
const Report kSecureReport{"wirerobot42", std::string("\xa9\x43\x3e\x37", 4), 173.21, 141.42};
const Report kPlainReport{"clearrobot17", std::string("\x59\x57\x5a\x67", 4), 223.61, 264.58};
const std::string kRobot = kSecureReport.robot;

std::string bytes_of(double v) {
  return std::string(reinterpret_cast<const char*>(&v), sizeof v);
}

// The payloads of every IPv4 UDP packet this host sends or receives while it runs (an AF_PACKET
// socket: needs CAP_NET_RAW). MQTT is TCP and not captured: only DDS traffic is looked at.
class UdpCapture {
 public:
  static std::unique_ptr<UdpCapture> start() {
    const int fd = ::socket(AF_PACKET, SOCK_DGRAM, htons(ETH_P_IP));
    if (fd < 0) return nullptr;
    timeval tv{0, 100000};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    return std::unique_ptr<UdpCapture>(new UdpCapture(fd));
  }
  ~UdpCapture() {
    stop_ = true;
    thread_.join();
    ::close(fd_);
  }
  bool contains(const std::string& needle) const {
    std::lock_guard lock(mutex_);
    return payloads_.find(needle) != std::string::npos;
  }
  size_t packets() const {
    std::lock_guard lock(mutex_);
    return packets_;
  }

 private:
  explicit UdpCapture(int fd) : fd_(fd), thread_([this] { loop(); }) {}
  void loop() {
    std::vector<char> buffer(65536);
    while (!stop_) {
      const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
      if (n < static_cast<ssize_t>(sizeof(iphdr))) continue;
      const auto* ip = reinterpret_cast<const iphdr*>(buffer.data());
      const size_t header = ip->ihl * 4u + 8u;  // IPv4 header, then the UDP header
      if (ip->protocol != IPPROTO_UDP || static_cast<size_t>(n) <= header) continue;
      std::lock_guard lock(mutex_);
      payloads_.append(buffer.data() + header, static_cast<size_t>(n) - header);
      payloads_ += '\n';  // no match across two packets
      ++packets_;
    }
  }

  int fd_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::string payloads_;
  size_t packets_ = 0;
  std::thread thread_;  // last: starts once the rest exists
};

class DdsSecurityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    group_.start("make-security", {"bash", SLAM_SOURCE_DIR "/compose/make-security.sh", security_});
    ASSERT_EQ(group_.wait_exit("make-security", 60s), 0) << group_.log("make-security");
    port_ = group_.start_mosquitto();
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "gateway log:\n" << group_.log("gateway") << "\n";
  }

  // `identity` empty: no security.
  std::vector<std::string> as(const std::string& identity, std::vector<std::string> argv) const {
    if (identity.empty()) return argv;
    argv.insert(argv.begin(), {"env", std::string(dds::kSecurityDirVariable) + "=" + security_,
                               std::string(dds::kIdentityVariable) + "=" + identity});
    return argv;
  }
  void start_gateway(bool secure) {
    group_.start("gateway", as(secure ? "gateway" : "",
                               {bin_path("slam-gateway"), "--domain", std::to_string(domain_.id()),
                                "--broker", "tcp://127.0.0.1:" + std::to_string(port_)}));
  }
  std::unique_ptr<dds::Participant> participant(const std::string& identity) {
    std::optional<dds::SecurityFiles> files;
    if (!identity.empty()) files = dds::SecurityFiles::in(security_, identity);
    auto p = dds::Participant::create(domain_.id(), "dds-security-test-" + identity, files);
    if (!p) throw std::runtime_error(p.message());
    return std::move(*p);
  }
  // The robot reports until `inbox` has one of its observations (false after the timeout).
  bool robot_reports_until_observed(const Inbox<RobotObservation>& inbox,
                                    const Report& report = kSecureReport) {
    MqttTestClient robot(port_, "dds-security-robot");
    if (robot.connect() != 0) return false;
    return wait_until(
        [&] {
          robot.publish("v1/robot/" + report.robot + "/adv", report.adv);
          return wait_until([&] { return inbox.size() > 0; }, 300ms);
        },
        30s);
  }

  DomainLease domain_;
  ProcessGroup group_;
  std::string security_ = group_.dir() + "/security";
  int port_ = 0;
};

TEST_F(DdsSecurityTest, ParticipantWithoutCertificateDiscoversAndReceivesNothing) {
  start_gateway(true);
  auto plain = participant("");
  auto secure = participant("viewer");
  Inbox<RobotObservation> plain_seen, secure_seen;
  Inbox<Heartbeat> plain_heartbeats;
  auto plain_reader = make_observation_inbox_reader(*plain, plain_seen);
  auto plain_heartbeat_reader = make_inbox_reader(*plain, dds::kHeartbeat, plain_heartbeats);
  auto secure_reader = make_observation_inbox_reader(*secure, secure_seen);

  ASSERT_TRUE(robot_reports_until_observed(secure_seen)) << "the secure reader got no observation";
  EXPECT_EQ(secure_seen.items().front().robot_id().to_string(), kRobot);
  EXPECT_EQ(plain_reader->matched_writers(), 0);
  EXPECT_EQ(plain_heartbeat_reader->matched_writers(), 0);
  EXPECT_EQ(plain_seen.size(), 0u);
  EXPECT_EQ(plain_heartbeats.size(), 0u)
      << "the gateway's heartbeats reached a participant without a certificate";
}

TEST_F(DdsSecurityTest, IdentityWithoutThePermissionCannotWriteTheTopic) {
  auto planner = participant("planner");
  Inbox<NavGoal> goals;
  auto goal_reader = make_inbox_reader(*planner, dds::kNavGoal, goals);

  // In this process: the mapper's identity may not create a goal writer at all.
  auto mapper = participant("mapper");
  EXPECT_FALSE(dds::make_writer(*mapper, dds::kNavGoal));

  // slamctl run as the mapper cannot send a goal; run as itself (an operator) it can.
  const auto goal = [&](const std::string& identity, const std::string& robot) {
    group_.start("slamctl-" + identity,
                 as(identity, {bin_path("slamctl"), "--domain", std::to_string(domain_.id()), "--timeout",
                               "10", "goal", robot, "explore"}));
    return group_.wait_exit("slamctl-" + identity, 60s);
  };
  EXPECT_NE(goal("mapper", "denied-robot"), 0) << group_.log("slamctl-mapper");
  EXPECT_NE(group_.log("slamctl-mapper").find("writer for slam/nav/goal"), std::string::npos)
      << group_.log("slamctl-mapper");
  EXPECT_EQ(goal("slamctl", "allowed-robot"), 0) << group_.log("slamctl-slamctl");
  ASSERT_TRUE(wait_until([&] { return goals.size() > 0; }, 20s)) << "the operator's goal never arrived";
  for (const NavGoal& g : goals.items()) EXPECT_EQ(g.robot_id().to_string(), "allowed-robot");
}

TEST_F(DdsSecurityTest, TamperedPermissionsStopAServiceWithOneLine) {
  const std::string permissions = security_ + "/identities/mapper.permissions.p7s";
  group_.start("tamper",
               {"sed", "-i", "s|<topic>slam/map/edit</topic>|<topic>slam/nav/goal</topic>|", permissions});
  ASSERT_EQ(group_.wait_exit("tamper", 10s), 0);
  group_.start("mapper", as("mapper", {bin_path("slam-mapper"), "--domain", std::to_string(domain_.id()),
                                       "--store", group_.dir() + "/map.db"}));
  EXPECT_EQ(group_.wait_exit("mapper", 30s), 1);
  const std::string log = group_.log("mapper");
  EXPECT_EQ(log, "slam-mapper: error: DDS security: " + permissions +
                     ": signature does not match the content (tampered with?)\n");
}

// Runs the gateway (secure or not) with a robot reporting while every UDP packet is captured.
class DdsWireTest : public DdsSecurityTest {
 protected:
  std::unique_ptr<UdpCapture> capture_while_reporting(bool secure, const Report& report) {
    auto capture = UdpCapture::start();
    if (!capture) return nullptr;
    start_gateway(secure);
    auto reader_participant = participant(secure ? "mapper" : "");
    Inbox<RobotObservation> seen;
    auto reader = make_observation_inbox_reader(*reader_participant, seen);
    EXPECT_TRUE(robot_reports_until_observed(seen, report));
    if (seen.size() > 0) {
      // The search looks for the exact doubles the samples carry.
      x_ = seen.items().front().pose().x();
      y_ = seen.items().front().pose().y();
      EXPECT_NEAR(x_, report.x, 1e-9);
      EXPECT_NEAR(y_, report.y, 1e-9);
    }
    return capture;
  }
  double x_ = 0, y_ = 0;  // the coordinates of the first observation the reader got
};

TEST_F(DdsWireTest, SecureDomainCarriesNoRobotIdOrCoordinateInClear) {
  auto capture = capture_while_reporting(true, kSecureReport);
  if (!capture)
    GTEST_SKIP() << "no packet capture here (AF_PACKET needs CAP_NET_RAW): " << std::strerror(errno);
  EXPECT_GT(capture->packets(), 0u);
  EXPECT_FALSE(capture->contains(kSecureReport.robot)) << "the robot id crossed the wire in clear";
  EXPECT_FALSE(capture->contains(bytes_of(x_))) << "x crossed the wire in clear";
  EXPECT_FALSE(capture->contains(bytes_of(y_))) << "y crossed the wire in clear";
}

TEST_F(DdsWireTest, PlainDomainCarriesThemInClear) {
  auto capture = capture_while_reporting(false, kPlainReport);
  if (!capture)
    GTEST_SKIP() << "no packet capture here (AF_PACKET needs CAP_NET_RAW): " << std::strerror(errno);
  EXPECT_TRUE(capture->contains(kPlainReport.robot));
  EXPECT_TRUE(capture->contains(bytes_of(x_)));
  EXPECT_TRUE(capture->contains(bytes_of(y_)));
}

}  // namespace
}  // namespace slam::testkit
