// The production broker settings (compose/mosquitto/mosquitto.conf and its acl) do what
// docs/deployment.md promises: only known users with the right password get in, a robot publishes
// only under its own id and reads only its own commands, and the gateway account reads every robot
// and commands every robot. A mosquitto per test runs the project's own files on a free loopback port
// with a password file made by mosquitto_passwd. "Not delivered" is proven by order, not by waiting:
// a permitted marker sent after the forbidden message arrives alone.
#include <MQTTClient.h>
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

#include "process_group.hpp"

namespace slam::testkit {
namespace {

namespace fs = std::filesystem;

const fs::path kMosquittoDir = fs::path(SLAM_SOURCE_DIR) / "compose" / "mosquitto";

struct Message {
  std::string topic;
  std::string payload;
};

// One account on the broker: synchronous paho, MQTT 3.1.1 (what robots and the gateway speak).
class Account {
 public:
  Account(int port, const std::string& user, const std::string& password) : user_(user), password_(password) {
    static int next_id = 0;
    const std::string url = "tcp://127.0.0.1:" + std::to_string(port);
    const std::string id = "acl-test-" + user + "-" + std::to_string(next_id++);
    EXPECT_EQ(MQTTClient_create(&client_, url.c_str(), id.c_str(), MQTTCLIENT_PERSISTENCE_NONE, nullptr),
              MQTTCLIENT_SUCCESS);
  }
  ~Account() {
    if (MQTTClient_isConnected(client_)) MQTTClient_disconnect(client_, 100);
    MQTTClient_destroy(&client_);
  }
  Account(const Account&) = delete;
  Account& operator=(const Account&) = delete;

  // The CONNACK code: 0 accepted, 4 bad user name or password, 5 not authorised.
  int connect() {
    MQTTClient_connectOptions options = MQTTClient_connectOptions_initializer;
    options.MQTTVersion = MQTTVERSION_3_1_1;  // no silent retry as 3.1 after a refusal
    options.cleansession = 1;
    options.keepAliveInterval = 10;
    options.connectTimeout = 2;
    if (!user_.empty()) options.username = user_.c_str();
    if (!password_.empty()) options.password = password_.c_str();
    return MQTTClient_connect(client_, &options);
  }
  // Filters may be refused in the SUBACK or only filtered at delivery; callers check what arrives.
  void subscribe(const std::string& filter) { MQTTClient_subscribe(client_, filter.c_str(), 1); }
  // QoS 1 and waits for the PUBACK: the broker has routed the message (or dropped it) by then.
  bool publish(const std::string& topic, const std::string& payload) {
    MQTTClient_deliveryToken token = 0;
    if (MQTTClient_publish(client_, topic.c_str(), static_cast<int>(payload.size()),
                           const_cast<char*>(payload.data()), 1, 0, &token) != MQTTCLIENT_SUCCESS)
      return false;
    return MQTTClient_waitForCompletion(client_, token, 2000) == MQTTCLIENT_SUCCESS;
  }
  // Every message up to and including the first one on `marker_topic`; nullopt if it never came.
  std::optional<std::vector<Message>> receive_until(const std::string& marker_topic) {
    std::vector<Message> got;
    const auto until = std::chrono::steady_clock::now() + 3s;
    while (std::chrono::steady_clock::now() < until) {
      char* topic = nullptr;
      int topic_len = 0;
      MQTTClient_message* message = nullptr;
      if (MQTTClient_receive(client_, &topic, &topic_len, &message, 200) != MQTTCLIENT_SUCCESS || !message)
        continue;
      got.push_back({topic_len > 0 ? std::string(topic, static_cast<size_t>(topic_len)) : std::string(topic),
                     std::string(static_cast<const char*>(message->payload),
                                 static_cast<size_t>(message->payloadlen))});
      MQTTClient_freeMessage(&message);
      MQTTClient_free(topic);
      if (got.back().topic == marker_topic) return got;
    }
    return std::nullopt;
  }

 private:
  std::string user_;
  std::string password_;
  MQTTClient client_ = nullptr;
};

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
  std::unique_ptr<Account> login(const std::string& user, const std::string& password) {
    auto account = std::make_unique<Account>(port_, user, password);
    EXPECT_EQ(account->connect(), MQTTCLIENT_SUCCESS) << user << " was refused; broker log:\n"
                                                      << group_.log("mosquitto");
    return account;
  }

  ProcessGroup group_;
  int port_ = 0;
};

TEST_F(BrokerAclTest, RobotPublishesUnderItsOwnIdAndTheGatewayReceivesIt) {
  auto gateway = login("gateway", "gateway-pw");
  gateway->subscribe("v1/robot/+/adv");
  gateway->subscribe("v2/robot/+/+");
  auto robot = login("robot-a", "a-pw");
  ASSERT_TRUE(robot->publish("v2/robot/robot-a/pose", R"({"x":1,"y":2,"theta":0})"));
  ASSERT_TRUE(robot->publish("v1/robot/robot-a/adv", std::string("\x01\x00\x02\x00", 4)));
  const auto got = gateway->receive_until("v1/robot/robot-a/adv");
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

  const auto at_gateway = gateway->receive_until("v1/robot/robot-a/adv");
  ASSERT_TRUE(at_gateway) << "robot-a's own message did not arrive";
  EXPECT_EQ(at_gateway->size(), 1u) << "forged robot-b messages were delivered: " << topics_of(*at_gateway);
  const auto at_b = robot_b->receive_until("v1/server/robot-b/cmd");
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

  const auto got = robot_a->receive_until("v1/server/robot-a/cmd");
  ASSERT_TRUE(got) << "robot-a's own command did not arrive";
  EXPECT_EQ(got->size(), 1u) << "robot-a read other robots' traffic: " << topics_of(*got);
}

TEST_F(BrokerAclTest, UnknownUserWrongPasswordAndAnonymousAreRefused) {
  const auto refused = [](int connack) { return connack == 4 || connack == 5; };
  Account unknown(port_, "robot-z", "z-pw");
  EXPECT_TRUE(refused(unknown.connect())) << "an unknown user was let in";
  Account wrong_password(port_, "robot-a", "b-pw");
  EXPECT_TRUE(refused(wrong_password.connect())) << "a wrong password was accepted";
  Account anonymous(port_, "", "");
  EXPECT_TRUE(refused(anonymous.connect())) << "an anonymous client was let in";
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
    const auto got = gateway->receive_until(sim1 ? "v1/robot/sim-2/adv" : "v1/robot/sim-1/adv");
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
