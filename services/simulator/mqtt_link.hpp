#pragma once
// One MQTT connection (paho async C client), as a robot holds it: connects in the background,
// reconnects after the broker restarts and subscribes again (clean sessions forget them), publishes
// QoS 0 and hands every inbound message to a callback. Used once per robot, or once for a whole
// multiplexed fleet.
#include <MQTTAsync.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"

namespace slam::sim {

struct MqttWill {
  std::string topic;
  std::string payload;
};

struct MqttLinkOptions {
  std::string broker;  // tcp://host:port
  std::string client_id;
  std::string username;  // empty: anonymous
  std::string password;
  std::vector<std::string> subscriptions;  // subscribed (QoS 1) after every connect
  std::optional<MqttWill> will;
};

// Process-wide gauges and counters the links update (owned by the service's Counters).
struct MqttLinkCounters {
  std::atomic<int64_t>* connected;   // links connected now
  std::atomic<int64_t>* reconnects;  // connects after the first, per link
  std::atomic<int64_t>* connect_failures;
};

class MqttLink {
 public:
  // Runs on a paho thread: copy what is needed and return quickly; must not throw.
  using MessageHandler = std::function<void(std::string_view topic, std::span<const uint8_t> payload)>;

  // Creates the client and starts connecting; an unreachable broker is retried, not an error.
  // Errors: a URL or client id paho refuses.
  static Result<std::unique_ptr<MqttLink>> create(MqttLinkOptions options, MessageHandler handler,
                                                  MqttLinkCounters counters);
  ~MqttLink();
  MqttLink(const MqttLink&) = delete;
  MqttLink& operator=(const MqttLink&) = delete;

  // QoS 0, not retained. False when not connected or paho refused the message (the caller counts it).
  bool publish(const std::string& topic, std::span<const uint8_t> payload);
  bool connected() const { return connected_.load(std::memory_order_acquire); }
  // Successful connects so far: a change tells the owner to resend what a fresh session needs.
  uint64_t connects() const { return connects_.load(std::memory_order_acquire); }

  // Starts a new connect attempt when the last one failed before the first session (paho's
  // automatic reconnect only covers sessions that were lost). Call from the owner's loop.
  void retry_connect(std::chrono::steady_clock::time_point now);
  // Asks for a clean disconnect (pending publishes are sent first); the destructor waits for it.
  void begin_disconnect();

 private:
  MqttLink() = default;
  bool start_connect();
  static void on_connected(void* context, char* cause);
  static void on_connection_lost(void* context, char* cause);
  static int on_message(void* context, char* topic, int topic_len, MQTTAsync_message* message);
  static void on_connect_failure(void* context, MQTTAsync_failureData* data);
  static void on_disconnected(void* context, MQTTAsync_successData* data);
  static void on_disconnect_failure(void* context, MQTTAsync_failureData* data);
  void set_connected(bool on);

  MQTTAsync client_ = nullptr;
  MqttLinkOptions options_;
  MessageHandler handler_;
  MqttLinkCounters counters_{};
  std::atomic<bool> connected_{false};
  std::atomic<uint64_t> connects_{0};
  std::atomic<bool> connect_failed_{false};
  std::atomic<bool> disconnect_done_{false};
  std::atomic<bool> disconnecting_{false};
  std::chrono::steady_clock::time_point next_retry_{};
};

}  // namespace slam::sim
