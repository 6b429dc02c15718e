#pragma once
// A small synchronous paho client for tests and benches: connect (tcp:// or, with a CA file,
// ssl://), subscribe, publish, and the messages that arrived, recorded on paho's thread and waited
// on by the caller.
#include <MQTTClient.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "inbox.hpp"

namespace slam::testkit {

struct MqttMessage {
  std::string topic;
  std::string payload;
  std::chrono::steady_clock::time_point received_at;
};

class MqttTestClient {
 public:
  // A client of the broker on 127.0.0.1:`port`; throws when paho cannot create it.
  MqttTestClient(int port, const std::string& client_id);
  // A client of the broker at `url` (tcp:// or ssl://); with `ca_file` non-empty, connect() speaks
  // TLS and verifies the broker's certificate with that CA. Throws when paho cannot create it.
  MqttTestClient(const std::string& url, const std::string& client_id, std::string ca_file = {});
  ~MqttTestClient();
  MqttTestClient(const MqttTestClient&) = delete;
  MqttTestClient& operator=(const MqttTestClient&) = delete;

  // Connects with a clean session over MQTT 3.1.1 (what robots and the gateway speak; no silent
  // retry as 3.1 after a refusal). Returns paho's code: 0 accepted, 4 bad user name or password,
  // 5 not authorised, negative when the broker could not be reached.
  int connect(const std::string& user = {}, const std::string& password = {});
  // TLS clients: present this PEM certificate and key to the broker at the next connect().
  void use_client_certificate(std::string cert_file, std::string key_file) {
    cert_file_ = std::move(cert_file);
    key_file_ = std::move(key_file);
  }
  bool connected() const;
  bool subscribe(const std::string& filter, int qos = 1);
  // With qos > 0, waits for the broker's acknowledgement: it has routed (or dropped) the message.
  bool publish(const std::string& topic, std::string_view payload, int qos = 1);
  bool publish(const std::string& topic, std::span<const uint8_t> payload, int qos = 1);

  // Every message received so far, in arrival order.
  std::vector<MqttMessage> messages() const { return inbox_.items(); }
  // The newest message on `topic`.
  std::optional<MqttMessage> last(const std::string& topic) const;
  // Waits until a message on `topic` has arrived (now or within `timeout`); the newest one.
  std::optional<MqttMessage> wait_for(const std::string& topic, std::chrono::milliseconds timeout) const;
  // The next message not yet returned by next(), in arrival order, waiting up to `timeout`.
  std::optional<MqttMessage> next(std::chrono::milliseconds timeout);

 private:
  static int arrived(void* self, char* topic, int topic_len, MQTTClient_message* message);

  MQTTClient client_ = nullptr;
  std::string ca_file_;
  std::string cert_file_;
  std::string key_file_;
  Inbox<MqttMessage> inbox_;
  size_t next_index_ = 0;
};

}  // namespace slam::testkit
