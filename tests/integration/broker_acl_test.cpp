// The production broker settings (compose/mosquitto/mosquitto.conf and its acl) do what
// docs/deployment.md promises: only known users with the right password get in, a robot publishes
// only under its own id and reads only its own commands, and the gateway account reads every robot
// and commands every robot. A mosquitto per test runs the project's own files on a free loopback port
// with a password file made by mosquitto_passwd. "Not delivered" is proven by order, not by waiting:
// a permitted marker sent after the forbidden message arrives alone.
#include <gtest/gtest.h>
#include <pwd.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "mqtt_test_client.hpp"
#include "process_group.hpp"

namespace slam::testkit {
namespace {

namespace fs = std::filesystem;

const fs::path kMosquittoDir = fs::path(SLAM_SOURCE_DIR) / "compose" / "mosquitto";

using Message = MqttMessage;

// Every message not read yet up to and including the first one on `marker_topic`; nullopt if it
// never came.
std::optional<std::vector<Message>> receive_until(MqttTestClient& account, const std::string& marker_topic) {
  std::vector<Message> got;
  while (auto message = account.next(3s)) {
    got.push_back(std::move(*message));
    if (got.back().topic == marker_topic) return got;
  }
  return std::nullopt;
}

std::string topics_of(const std::vector<Message>& messages) {
  std::string out;
  for (const auto& m : messages) out += m.topic + " ";
  return out;
}

bool contains_topic(const std::vector<Message>& messages, const std::string& topic) {
  for (const auto& m : messages)
    if (m.topic == topic) return true;
  return false;
}

class BrokerAclTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string passwords = group_.dir() + "/passwords";
    const std::pair<std::string, std::string> users[] = {{"gateway", "gateway-pw"},
                                                         {"robot-a", "a-pw"},
                                                         {"robot-b", "b-pw"},
                                                         {"sim-1", "sim-pw"},
                                                         {"sim-2", "sim-pw"}};
    for (const auto& [user, password] : users) {
      std::vector<std::string> argv{"mosquitto_passwd", "-b", passwords, user, password};
      if (!fs::exists(passwords)) argv.insert(argv.begin() + 1, "-c");
      const std::string name = "passwd-" + user;
      group_.start(name, argv);
      ASSERT_EQ(group_.wait_exit(name, 10s), 0) << group_.log(name);
    }
    port_ = free_tcp_port();
    const std::string conf = group_.dir() + "/mosquitto.conf";
    ASSERT_NO_FATAL_FAILURE(write_config(conf, passwords));
    group_.start("mosquitto", {"mosquitto", "-c", conf});
    ASSERT_TRUE(wait_port_open(port_, 5s)) << "mosquitto did not open port " << port_;
  }

  // compose/mosquitto/mosquitto.conf with only the container paths and the port replaced, so the
  // test runs the production settings themselves; each of the replaced directives must be there.
  void write_config(const std::string& path, const std::string& passwords) {
    std::ifstream in(kMosquittoDir / "mosquitto.conf");
    ASSERT_TRUE(in) << "cannot read " << kMosquittoDir / "mosquitto.conf";
    std::ofstream out(path);
    bool listener = false, password_file = false, acl_file = false, no_anonymous = false;
    for (std::string line; std::getline(in, line);) {
      std::istringstream words(line);
      std::string key, value;
      words >> key >> value;
      if (key == "listener") {
        listener = true;
        line = "listener " + std::to_string(port_) + " 127.0.0.1";
      } else if (key == "password_file") {
        password_file = true;
        line = "password_file " + passwords;
      } else if (key == "acl_file") {
        acl_file = true;
        line = "acl_file " + (kMosquittoDir / "acl").string();
      } else if (key == "allow_anonymous") {
        no_anonymous = value == "false";
      }
      out << line << "\n";
    }
    out << "log_dest stderr\n";
    // Started as root, mosquitto would drop to user "mosquitto", who cannot read the test's
    // private directory; stay the user who runs the test (ignored when that is not root).
    if (const passwd* pw = getpwuid(geteuid())) out << "user " << pw->pw_name << "\n";
    EXPECT_TRUE(listener && password_file && acl_file)
        << "mosquitto.conf must set listener, password_file and acl_file";
    EXPECT_TRUE(no_anonymous) << "mosquitto.conf must say allow_anonymous false";
  }

  // A connected account (the test fails if the broker refuses it).
  std::unique_ptr<MqttTestClient> login(const std::string& user, const std::string& password) {
    auto account = std::make_unique<MqttTestClient>(port_, next_client_id(user));
    EXPECT_EQ(account->connect(user, password), 0) << user << " was refused; broker log:\n"
                                                   << group_.log("mosquitto");
    return account;
  }

  std::string next_client_id(const std::string& user) {
    return "acl-test-" + user + "-" + std::to_string(clients_++);
  }

  ProcessGroup group_;
  int port_ = 0;
  int clients_ = 0;
};

TEST_F(BrokerAclTest, RobotPublishesUnderItsOwnIdAndTheGatewayReceivesIt) {
  auto gateway = login("gateway", "gateway-pw");
  gateway->subscribe("v1/robot/+/adv");
  gateway->subscribe("v2/robot/+/+");
  auto robot = login("robot-a", "a-pw");
  ASSERT_TRUE(robot->publish("v2/robot/robot-a/pose", R"({"x":1,"y":2,"theta":0})"));
  ASSERT_TRUE(robot->publish("v1/robot/robot-a/adv", std::string("\x01\x00\x02\x00", 4)));
  const auto got = receive_until(*gateway, "v1/robot/robot-a/adv");
  ASSERT_TRUE(got) << "the gateway did not receive robot-a's v1 message";
  EXPECT_TRUE(contains_topic(*got, "v2/robot/robot-a/pose")) << topics_of(*got);
  EXPECT_EQ(got->back().payload, std::string("\x01\x00\x02\x00", 4));
}

TEST_F(BrokerAclTest, RobotCannotPublishUnderAnotherRobotsId) {
  auto gateway = login("gateway", "gateway-pw");
  gateway->subscribe("v1/robot/+/adv");
  gateway->subscribe("v2/robot/+/+");
  auto robot_b = login("robot-b", "b-pw");
  robot_b->subscribe("v1/server/robot-b/cmd");
  auto robot_a = login("robot-a", "a-pw");
  // The broker acknowledges forbidden publications too (MQTT 3.1.1 has no refusal); it drops them.
  ASSERT_TRUE(robot_a->publish("v1/robot/robot-b/adv", std::string("\x05\x00\x05\x00", 4)));
  ASSERT_TRUE(robot_a->publish("v2/robot/robot-b/status", R"({"state":"offline"})"));
  ASSERT_TRUE(robot_a->publish("v1/server/robot-b/cmd", std::string("\x09\x00\x09\x00", 4)));
  ASSERT_TRUE(robot_a->publish("v1/robot/robot-a/adv", std::string("\x01\x00\x01\x00", 4)));
  ASSERT_TRUE(gateway->publish("v1/server/robot-b/cmd", std::string("\x02\x00\x02\x00", 4)));

  const auto at_gateway = receive_until(*gateway, "v1/robot/robot-a/adv");
  ASSERT_TRUE(at_gateway) << "robot-a's own message did not arrive";
  EXPECT_EQ(at_gateway->size(), 1u) << "forged robot-b messages were delivered: " << topics_of(*at_gateway);
  const auto at_b = receive_until(*robot_b, "v1/server/robot-b/cmd");
  ASSERT_TRUE(at_b) << "the gateway's command to robot-b did not arrive";
  EXPECT_EQ(at_b->front().payload, std::string("\x02\x00\x02\x00", 4))
      << "robot-a's forged command reached robot-b";
}

TEST_F(BrokerAclTest, RobotReadsOnlyItsOwnCommands) {
  auto robot_a = login("robot-a", "a-pw");
  robot_a->subscribe("v1/server/robot-a/cmd");
  for (const char* filter : {"v1/server/+/cmd", "v2/server/#", "v1/robot/#", "v2/robot/#"})
    robot_a->subscribe(filter);
  auto robot_b = login("robot-b", "b-pw");
  auto gateway = login("gateway", "gateway-pw");
  ASSERT_TRUE(robot_b->publish("v1/robot/robot-b/adv", std::string("\x03\x00\x03\x00", 4)));
  ASSERT_TRUE(robot_b->publish("v2/robot/robot-b/pose", R"({"x":3,"y":3,"theta":0})"));
  ASSERT_TRUE(gateway->publish("v1/server/robot-b/cmd", std::string("\x04\x00\x04\x00", 4)));
  ASSERT_TRUE(gateway->publish("v2/server/robot-b/waypoint", R"({"x":4,"y":4})"));
  ASSERT_TRUE(gateway->publish("v1/server/robot-a/cmd", std::string("\x06\x00\x06\x00", 4)));

  const auto got = receive_until(*robot_a, "v1/server/robot-a/cmd");
  ASSERT_TRUE(got) << "robot-a's own command did not arrive";
  EXPECT_EQ(got->size(), 1u) << "robot-a read other robots' traffic: " << topics_of(*got);
}

TEST_F(BrokerAclTest, UnknownUserWrongPasswordAndAnonymousAreRefused) {
  const auto refused = [](int connack) { return connack == 4 || connack == 5; };
  MqttTestClient unknown(port_, next_client_id("unknown"));
  EXPECT_TRUE(refused(unknown.connect("robot-z", "z-pw"))) << "an unknown user was let in";
  MqttTestClient wrong_password(port_, next_client_id("wrong_password"));
  EXPECT_TRUE(refused(wrong_password.connect("robot-a", "b-pw"))) << "a wrong password was accepted";
  MqttTestClient anonymous(port_, next_client_id("anonymous"));
  EXPECT_TRUE(refused(anonymous.connect("", ""))) << "an anonymous client was let in";
  // And the right password still works, so the refusals above are about the credentials.
  login("robot-a", "a-pw");
}

TEST_F(BrokerAclTest, SimulatedRobotsLogInUnderTheirOwnIds) {
  // The compose `sim` profile: slam-simulator --mqtt-password, each robot its own broker user.
  auto gateway = login("gateway", "gateway-pw");
  gateway->subscribe("v1/robot/+/adv");
  DomainLease lease;
  group_.start("simulator",
               {bin_path("slam-simulator"), "--domain", std::to_string(lease.id()), "--broker",
                "tcp://127.0.0.1:" + std::to_string(port_), "--robots", "2", "--mqtt-password", "sim-pw"});
  bool sim1 = false, sim2 = false;
  for (int i = 0; i < 20 && !(sim1 && sim2); ++i) {
    const auto got = receive_until(*gateway, sim1 ? "v1/robot/sim-2/adv" : "v1/robot/sim-1/adv");
    if (!got) continue;
    sim1 = sim1 || contains_topic(*got, "v1/robot/sim-1/adv");
    sim2 = sim2 || contains_topic(*got, "v1/robot/sim-2/adv");
  }
  EXPECT_TRUE(sim1 && sim2) << "simulated robots' reports did not reach the gateway; broker log:\n"
                            << group_.log("mosquitto") << "\nsimulator log:\n"
                            << group_.log("simulator");
}

}  // namespace
}  // namespace slam::testkit
