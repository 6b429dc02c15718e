// slam::mqtt::Connection against a real mosquitto: connect, subscribe, publish round trip, and
// reconnection with re-subscription after the broker restarts.
#include "common/mqtt/mqtt_connection.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include "inbox.hpp"
#include "process_group.hpp"

namespace slam::mqtt {
namespace {

using namespace std::chrono_literals;
using testkit::ProcessGroup;
using testkit::wait_until;

std::span<const std::uint8_t> bytes(const std::string& text) {
  return {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()};
}

// A connection whose owner loop (poll) runs on its own thread, recording what arrives.
class Peer {
 public:
  Peer(int port, const std::string& client_id, std::vector<std::string> subscriptions) {
    ConnectionOptions options;
    options.broker = "tcp://127.0.0.1:" + std::to_string(port);
    options.client_id = client_id;
    options.subscriptions = std::move(subscriptions);
    options.reconnect_min_s = 0.1;
    options.reconnect_max_s = 0.5;
    Callbacks callbacks;
    callbacks.message = [this](std::string_view topic, std::span<const std::uint8_t> payload) {
      received_.push(std::string(topic) + "=" + std::string(payload.begin(), payload.end()));
    };
    callbacks.connected = [this](bool reconnect) {
      if (reconnect) ++reconnect_callbacks_;
    };
    callbacks.lost = [this](const std::string&) { ++lost_callbacks_; };
    auto created = Connection::create(std::move(options), std::move(callbacks));
    EXPECT_TRUE(created) << created.message();
    if (created) connection_ = std::move(*created);
    loop_ = std::thread([this] {
      while (!stop_) {
        if (connection_) connection_->poll(Connection::Clock::now());
        std::this_thread::sleep_for(10ms);
      }
    });
  }
  ~Peer() {
    stop_ = true;
    loop_.join();
  }

  Connection& connection() { return *connection_; }
  bool received(const std::string& entry) const {
    return received_.last([&](const std::string& r) { return r == entry; }).has_value();
  }
  int reconnect_callbacks() const { return reconnect_callbacks_; }
  int lost_callbacks() const { return lost_callbacks_; }

 private:
  // Declared first: it outlives the connection, whose callbacks feed it.
  testkit::Inbox<std::string> received_;
  std::unique_ptr<Connection> connection_;
  std::atomic<int> reconnect_callbacks_{0};
  std::atomic<int> lost_callbacks_{0};
  std::atomic<bool> stop_{false};
  std::thread loop_;
};

// Publishes `payload` until `receiver` got it (QoS 0 before a SUBACK may be lost: retried).
bool round_trip(Peer& sender, Peer& receiver, const std::string& topic, const std::string& payload) {
  return wait_until(
      [&] {
        (void)sender.connection().publish(topic, bytes(payload), 0, false);
        return receiver.received(topic + "=" + payload);
      },
      10s, 50ms);
}

TEST(MqttConnection, RejectsInvalidOptions) {
  ConnectionOptions options;
  options.client_id = "bad";
  options.qos = 3;
  EXPECT_FALSE(Connection::create(options, {}));
  options.qos = 1;
  options.client_id.clear();
  EXPECT_FALSE(Connection::create(options, {}));
}

TEST(MqttConnection, PublishesAndReceivesThroughTheBroker) {
  ProcessGroup group;
  const int port = group.start_mosquitto();
  Peer receiver(port, "receiver", {"test/+/in"});
  Peer sender(port, "sender", {});
  ASSERT_TRUE(
      wait_until([&] { return receiver.connection().connected() && sender.connection().connected(); }, 10s));
  EXPECT_EQ(receiver.connection().filters(), std::vector<std::string>{"test/+/in"});
  EXPECT_TRUE(round_trip(sender, receiver, "test/a/in", "hello"));

  // A filter added at run time is subscribed at once; a removed one no longer delivers.
  ASSERT_TRUE(receiver.connection().subscribe("extra/#", 1));
  EXPECT_TRUE(round_trip(sender, receiver, "extra/x", "more"));
  ASSERT_TRUE(receiver.connection().unsubscribe("extra/#"));
  EXPECT_FALSE(receiver.connection().unsubscribe("extra/#"));
  EXPECT_EQ(receiver.connection().filters(), std::vector<std::string>{"test/+/in"});
}

TEST(MqttConnection, ReconnectsAndSubscribesAgainAfterTheBrokerRestarts) {
  ProcessGroup group;
  const int port = group.start_mosquitto();
  Peer receiver(port, "receiver", {"test/+/in"});
  ASSERT_TRUE(receiver.connection().subscribe("added/#", 1));
  Peer sender(port, "sender", {});
  ASSERT_TRUE(
      wait_until([&] { return receiver.connection().connected() && sender.connection().connected(); }, 10s));
  ASSERT_TRUE(round_trip(sender, receiver, "test/a/in", "before"));

  group.stop("mosquitto");
  ASSERT_TRUE(wait_until([&] { return !receiver.connection().connected(); }, 10s));
  EXPECT_FALSE(sender.connection().publish("test/a/in", bytes("lost"), 0, false));
  group.restart_mosquitto("mosquitto", port);

  ASSERT_TRUE(
      wait_until([&] { return receiver.connection().connected() && sender.connection().connected(); }, 15s))
      << group.log("mosquitto");
  EXPECT_GE(receiver.connection().reconnects(), 1u);
  EXPECT_GE(receiver.reconnect_callbacks(), 1);
  EXPECT_GE(receiver.lost_callbacks(), 1);
  // Clean session: both the configured and the run-time filter were subscribed again.
  EXPECT_TRUE(round_trip(sender, receiver, "test/b/in", "after"));
  EXPECT_TRUE(round_trip(sender, receiver, "added/x", "after"));
}

}  // namespace
}  // namespace slam::mqtt
