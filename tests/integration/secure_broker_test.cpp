// The secure-mode broker (compose/mosquitto/mosquitto-secure.conf with the files of
// compose/make-security.sh, filled in as compose/launch.sh does) refuses what docs/security.md says
// it refuses: plain TCP, a client that trusts another CA, anonymous clients, expired or foreign
// client certificates, and a robot publishing as another robot. A valid robot certificate, and a
// simulator that verifies the broker against the CA, get through.
#include <gtest/gtest.h>
#include <pwd.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mqtt_test_client.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

namespace fs = std::filesystem;

const fs::path kCompose = fs::path(SLAM_SOURCE_DIR) / "compose";

class SecureBrokerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(make_security(security_));
    ASSERT_NO_FATAL_FAILURE(make_security(other_));
    ASSERT_NO_FATAL_FAILURE(run("robot-cert", "bash " + (kCompose / "make-security.sh").string() + " " +
                                                  security_ + " robot robot-a && bash " +
                                                  (kCompose / "make-security.sh").string() + " " + other_ +
                                                  " robot robot-a"));
    ASSERT_NO_FATAL_FAILURE(
        run("passwords", "printf 'gateway:gateway-pw\\nrobot-a:a-pw\\nrobot-b:b-pw\\nsim-1:sim-pw\\n' > " +
                             security_ + "/mqtt-passwords && mosquitto_passwd -U " + security_ +
                             "/mqtt-passwords"));
    port_ = free_tcp_port();
    do mutual_port_ = free_tcp_port();
    while (mutual_port_ == port_);
    const std::string conf = group_.dir() + "/mosquitto.conf";
    // The same substitutions as compose/launch.sh --secure.
    ASSERT_NO_FATAL_FAILURE(
        run("conf", "sed -e 's|^listener 8883|listener " + std::to_string(port_) +
                        " 127.0.0.1|' -e 's|^listener 8884|listener " + std::to_string(mutual_port_) +
                        " 127.0.0.1|' -e 's|SECURITY/|" + security_ + "/|' -e 's|^acl_file .*|acl_file " +
                        (kCompose / "mosquitto" / "acl").string() + "|' " +
                        (kCompose / "mosquitto" / "mosquitto-secure.conf").string() + " > " + conf));
    std::ofstream(conf, std::ios::app) << "log_dest stderr\n"
                                       << "user " << getpwuid(geteuid())->pw_name << "\n";
    group_.start("mosquitto", {"mosquitto", "-c", conf});
    ASSERT_TRUE(wait_port_open(port_, 10s) && wait_port_open(mutual_port_, 10s)) << group_.log("mosquitto");
  }
  void TearDown() override {
    if (HasFailure()) std::cerr << "mosquitto log:\n" << group_.log("mosquitto") << "\n";
  }

  // Runs a shell command line to completion; the test fails with its output if it fails.
  void run(const std::string& name, const std::string& command) {
    group_.start(name, {"bash", "-c", "set -e; " + command});
    ASSERT_EQ(group_.wait_exit(name, 60s), 0) << group_.log(name);
  }
  void make_security(const std::string& dir) {
    run("make-" + fs::path(dir).filename().string(),
        "bash " + (kCompose / "make-security.sh").string() + " " + dir);
  }

  std::string tls_url() const { return "ssl://127.0.0.1:" + std::to_string(port_); }
  std::string mutual_tls_url() const { return "ssl://127.0.0.1:" + std::to_string(mutual_port_); }
  std::string ca(const std::string& dir) const { return dir + "/ca.crt"; }
  // A client of the TLS listener trusting `ca_file`, with the next client id.
  std::unique_ptr<MqttTestClient> client(const std::string& ca_file) {
    return std::make_unique<MqttTestClient>(tls_url(), "secure-test-" + std::to_string(clients_++), ca_file);
  }
  // A client of the mutual-TLS listener presenting `certificate` (and the key beside it, .key).
  std::unique_ptr<MqttTestClient> robot_with(const std::string& certificate, const std::string& key) {
    auto c = std::make_unique<MqttTestClient>(mutual_tls_url(), "secure-test-" + std::to_string(clients_++),
                                              ca(security_));
    if (!certificate.empty()) c->use_client_certificate(certificate, key);
    return c;
  }
  std::unique_ptr<MqttTestClient> login(const std::string& user, const std::string& password) {
    auto c = client(ca(security_));
    EXPECT_EQ(c->connect(user, password), 0) << user << " was refused";
    return c;
  }

  ProcessGroup group_;
  std::string security_ = group_.dir() + "/security";
  std::string other_ = group_.dir() + "/other";
  int port_ = 0;         // TLS, user name and password
  int mutual_port_ = 0;  // mutual TLS: the client certificate is the credential
  int clients_ = 0;
};

TEST_F(SecureBrokerTest, PlainTcpIsRefused) {
  MqttTestClient plain("tcp://127.0.0.1:" + std::to_string(port_), "secure-test-plain");
  EXPECT_NE(plain.connect("robot-a", "a-pw"), 0);
  EXPECT_FALSE(plain.connected());
}

TEST_F(SecureBrokerTest, ClientTrustingAnotherCaRefusesTheBroker) {
  auto c = client(ca(other_));
  EXPECT_NE(c->connect("robot-a", "a-pw"), 0);
  // The same login with the right CA is accepted: only the CA differed.
  EXPECT_EQ(client(ca(security_))->connect("robot-a", "a-pw"), 0);
}

TEST_F(SecureBrokerTest, AnonymousAndWrongPasswordAreRefused) {
  EXPECT_NE(client(ca(security_))->connect(), 0);
  EXPECT_NE(client(ca(security_))->connect("robot-a", "b-pw"), 0);
}

TEST_F(SecureBrokerTest, RobotCertificateOfTheCaIsItsCredential) {
  auto gateway = login("gateway", "gateway-pw");
  ASSERT_TRUE(gateway->subscribe("v1/robot/+/adv"));
  auto robot = robot_with(security_ + "/robots/robot-a.crt", security_ + "/robots/robot-a.key");
  ASSERT_EQ(robot->connect(), 0);
  // Its certificate names it robot-a: the ACL lets it publish as robot-a only.
  ASSERT_TRUE(robot->publish("v1/robot/robot-b/adv", std::string("\x01\x00\x02\x00", 4)));
  ASSERT_TRUE(robot->publish("v1/robot/robot-a/adv", std::string("\x03\x00\x04\x00", 4)));
  ASSERT_TRUE(gateway->wait_for("v1/robot/robot-a/adv", 10s)) << "robot-a's own message never arrived";
  EXPECT_FALSE(gateway->last("v1/robot/robot-b/adv")) << "robot-a published as robot-b";
}

TEST_F(SecureBrokerTest, MutualTlsRefusesAClientWithoutCertificate) {
  EXPECT_NE(robot_with("", "")->connect("robot-a", "a-pw"), 0);
}

TEST_F(SecureBrokerTest, ExpiredClientCertificateIsRefused) {
  // robot-a's own key and name, signed by the right CA, valid until yesterday.
  const std::string robots = security_ + "/robots";
  ASSERT_NO_FATAL_FAILURE(
      run("expired", "cd " + robots +
                         " && openssl req -new -key robot-a.key -subj /CN=robot-a -out old.csr"
                         " && openssl x509 -req -in old.csr -CA ../ca.crt -CAkey ../ca.key -days -1"
                         " -out expired.crt"));
  EXPECT_NE(robot_with(robots + "/expired.crt", robots + "/robot-a.key")->connect(), 0);
  // The valid certificate of the same key gets in: only the dates differed.
  EXPECT_EQ(robot_with(robots + "/robot-a.crt", robots + "/robot-a.key")->connect(), 0);
}

TEST_F(SecureBrokerTest, ClientCertificateOfAnotherCaIsRefused) {
  EXPECT_NE(robot_with(other_ + "/robots/robot-a.crt", other_ + "/robots/robot-a.key")->connect(), 0);
}

TEST_F(SecureBrokerTest, RobotCannotPublishAsAnotherRobot) {
  auto gateway = login("gateway", "gateway-pw");
  ASSERT_TRUE(gateway->subscribe("v1/robot/+/adv"));
  auto robot = login("robot-a", "a-pw");
  ASSERT_TRUE(robot->publish("v1/robot/robot-b/adv", std::string("\x01\x00\x02\x00", 4)));
  // Sent after the forbidden one: when it arrives alone, the forbidden one was dropped.
  ASSERT_TRUE(robot->publish("v1/robot/robot-a/adv", std::string("\x03\x00\x04\x00", 4)));
  ASSERT_TRUE(gateway->wait_for("v1/robot/robot-a/adv", 10s)) << "robot-a's own message never arrived";
  EXPECT_FALSE(gateway->last("v1/robot/robot-b/adv")) << "robot-a published as robot-b";
}

TEST_F(SecureBrokerTest, SimulatorVerifiesTheBrokerAgainstTheCa) {
  auto gateway = login("gateway", "gateway-pw");
  ASSERT_TRUE(gateway->subscribe("v1/robot/+/adv"));
  DomainLease domain;
  group_.start("simulator",
               {bin_path("slam-simulator"), "--domain", std::to_string(domain.id()), "--broker", tls_url(),
                "--tls-ca-file", ca(security_), "--mqtt-password", "sim-pw", "--robots", "1"});
  EXPECT_TRUE(gateway->wait_for("v1/robot/sim-1/adv", 20s)) << group_.log("simulator");
}

TEST_F(SecureBrokerTest, SimulatorTrustingAnotherCaDeliversNothing) {
  auto gateway = login("gateway", "gateway-pw");
  ASSERT_TRUE(gateway->subscribe("v1/robot/+/adv"));
  DomainLease domain;
  group_.start("simulator", {bin_path("slam-simulator"), "--domain", std::to_string(domain.id()), "--broker",
                             tls_url(), "--tls-ca-file", ca(other_), "--mqtt-password", "sim-pw", "--robots",
                             "1", "--log-level", "debug"});
  // The simulator's connection failed (it keeps retrying); a robot of the right CA gets through after.
  ASSERT_TRUE(wait_until([&] { return group_.log("simulator").find("failed") != std::string::npos; }, 20s))
      << group_.log("simulator");
  auto robot = login("robot-a", "a-pw");
  ASSERT_TRUE(robot->publish("v1/robot/robot-a/adv", std::string("\x03\x00\x04\x00", 4)));
  ASSERT_TRUE(gateway->wait_for("v1/robot/robot-a/adv", 10s));
  EXPECT_TRUE(group_.running("simulator"));
  EXPECT_FALSE(gateway->last("v1/robot/sim-1/adv"))
      << "the simulator connected to a broker its CA did not sign";
}

}  // namespace
}  // namespace slam::testkit
