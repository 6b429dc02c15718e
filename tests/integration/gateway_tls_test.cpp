// slam-gateway over a real TLS listener: a throwaway CA and server certificate are made with the
// openssl command line, mosquitto serves TLS only, and a robot's message sent over TLS reaches DDS.
// With a CA that did not sign the broker's certificate the gateway refuses the broker: it says so in
// its log and delivers nothing.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/fastdds/fast_topics.hpp"
#include "fastdds_inbox.hpp"
#include "mqtt_test_client.hpp"
#include "observation_batches.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

// v1 adv: position (1.00, 2.00) m as int16 LE centimetres.
const std::string kAdv("\x64\x00\xc8\x00", 4);

class GatewayTlsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(make_certificates());
    port = free_tcp_port();
    const std::string config = dir + "/mosquitto.conf";
    std::ofstream(config) << "listener " << port << " 127.0.0.1\n"
                          << "allow_anonymous true\n"
                          << "persistence false\n"
                          << "log_dest stderr\n"
                          // Started as root, mosquitto would read the keys as 'mosquitto', which may not
                          // enter the private test directory (ignored when not root).
                          << "user root\n"
                          << "cafile " << dir << "/ca.crt\n"
                          << "certfile " << dir << "/server.crt\n"
                          << "keyfile " << dir << "/server.key\n";
    group.start("mosquitto", {"mosquitto", "-c", config});
    ASSERT_TRUE(wait_port_open(port, 10s)) << group.log("mosquitto");

    auto p = dds::Participant::create(domain.id(), "gateway-tls-test");
    ASSERT_TRUE(p) << p.message();
    participant = std::move(*p);
    observation_reader = make_observation_inbox_reader(*participant, observations_seen);
    subscription_reader = make_inbox_reader(*participant, dds::kMqttSubscriptions, subscriptions_seen);
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "gateway log:\n" << group.log("gateway") << "\n";
  }

  // Runs one openssl command to completion in the test's directory.
  void openssl(const std::string& name, std::vector<std::string> args) {
    args.insert(args.begin(), "openssl");
    group.start(name, args);
    ASSERT_EQ(group.wait_exit(name, 30s), 0) << group.log(name);
  }
  // ca.crt signs server.crt (for 127.0.0.1); other-ca.crt is an unrelated CA.
  void make_certificates() {
    const auto self_signed_ca = [&](const std::string& name, const std::string& cn) {
      openssl(name, {"req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes",
                     "-keyout", dir + "/" + name + ".key", "-out", dir + "/" + name + ".crt", "-days", "1",
                     "-subj", "/CN=" + cn});
    };
    ASSERT_NO_FATAL_FAILURE(self_signed_ca("ca", "slamfleet test CA"));
    ASSERT_NO_FATAL_FAILURE(self_signed_ca("other-ca", "unrelated test CA"));
    ASSERT_NO_FATAL_FAILURE(openssl(
        "csr", {"req", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes", "-keyout",
                dir + "/server.key", "-out", dir + "/server.csr", "-subj", "/CN=127.0.0.1"}));
    std::ofstream(dir + "/server.ext") << "subjectAltName=IP:127.0.0.1\n";
    ASSERT_NO_FATAL_FAILURE(openssl(
        "sign",
        {"x509", "-req", "-in", dir + "/server.csr", "-CA", dir + "/ca.crt", "-CAkey", dir + "/ca.key",
         "-CAcreateserial", "-out", dir + "/server.crt", "-days", "1", "-extfile", dir + "/server.ext"}));
  }
  void start_gateway(const std::string& ca_file, std::vector<std::string> extra = {}) {
    std::vector<std::string> argv{
        bin_path("slam-gateway"), "--domain", std::to_string(domain.id()), "--broker", broker(),
        "--tls-ca-file",          ca_file,    "--reconnect-max-s",         "1"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    group.start("gateway", argv);
  }
  std::string broker() const { return "ssl://127.0.0.1:" + std::to_string(port); }
  bool gateway_connected() const {
    const auto latest = subscriptions_seen.last([](const MqttSubscriptions&) { return true; });
    return latest && latest->connected();
  }
  bool observed(const std::string& robot) const {
    return observations_seen
        .last([&](const RobotObservation& o) { return o.robot_id().to_string() == robot; })
        .has_value();
  }
  // Gateway log lines naming the broker; `problems_only`: warnings and errors only.
  size_t broker_lines(bool problems_only) {
    std::istringstream log(group.log("gateway"));
    size_t n = 0;
    for (std::string line; std::getline(log, line);) {
      const bool problem =
          line.find("[warning]") != std::string::npos || line.find("[error]") != std::string::npos;
      if ((problem || !problems_only) && line.find(broker()) != std::string::npos) ++n;
    }
    return n;
  }

  DomainLease domain;
  ProcessGroup group;
  std::string dir = group.dir();
  int port = 0;
  Inbox<RobotObservation> observations_seen;
  Inbox<MqttSubscriptions> subscriptions_seen;
  std::unique_ptr<dds::Participant> participant;
  std::unique_ptr<dds::Reader<RobotObservationBatch>> observation_reader;
  std::unique_ptr<dds::Reader<MqttSubscriptions>> subscription_reader;
};

TEST_F(GatewayTlsTest, RobotMessageOverTlsReachesDds) {
  start_gateway(dir + "/ca.crt");
  ASSERT_TRUE(wait_until([&] { return gateway_connected(); }, 20s)) << "gateway never connected over TLS";

  MqttTestClient robot(broker(), "tls-robot", dir + "/ca.crt");
  ASSERT_EQ(robot.connect(), 0) << "the robot's TLS connection failed";
  // The gateway's subscription may still be on its way to the broker: send until it arrives.
  ASSERT_TRUE(wait_until(
      [&] {
        EXPECT_TRUE(robot.publish("v1/robot/tls1/adv", kAdv));
        return wait_until([&] { return observed("tls1"); }, 300ms);
      },
      15s));
}

TEST_F(GatewayTlsTest, GatewayRefusesABrokerItsCaDidNotSign) {
  start_gateway(dir + "/other-ca.crt", {"--log-level", "debug"});
  ASSERT_TRUE(wait_until([&] { return broker_lines(true) >= 1; }, 20s)) << "no failed connection logged";

  // The broker itself is fine: a robot trusting the right CA gets through to it.
  MqttTestClient robot(broker(), "tls-robot", dir + "/ca.crt");
  ASSERT_EQ(robot.connect(), 0);
  ASSERT_TRUE(robot.publish("v1/robot/tls2/adv", kAdv));
  // Two more attempts (each logs a line naming the broker; backoff at most 1 s) after the robot's
  // message, and still nothing came through.
  const size_t before = broker_lines(false);
  ASSERT_TRUE(wait_until([&] { return broker_lines(false) >= before + 2; }, 20s));
  EXPECT_TRUE(group.running("gateway"));
  EXPECT_FALSE(gateway_connected());
  EXPECT_FALSE(observed("tls2"));
}

}  // namespace
}  // namespace slam::testkit
