#pragma once
// The gateway's one MQTT connection (paho-mqtt-c asynchronous API, with TLS). Owns reconnection:
// after the broker goes away it retries with exponential backoff and subscribes again (a clean
// session forgets subscriptions), logging each state change once. Every paho callback is caught
// whole: no exception crosses back into the C library.
#include <MQTTAsync.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "common/core/result.hpp"
#include "gateway/backoff.hpp"
#include "gateway/gateway_options.hpp"

namespace slam::gateway {

class MqttClient {
 public:
  // Called on paho's receive thread for every message; `topic` and `payload` die when it returns.
  using MessageCallback = std::function<void(std::string_view topic, std::span<const std::uint8_t> payload)>;

  // Creates the client and starts connecting in the background (a broker that is down at start
  // is retried like one that went away). Errors: bad URL or client id, TLS without paho-mqtt3as.
  static Result<std::unique_ptr<MqttClient>> create(const MqttOptions& options, std::string client_id,
                                                    MessageCallback on_message);
  ~MqttClient();
  MqttClient(const MqttClient&) = delete;
  MqttClient& operator=(const MqttClient&) = delete;

  // Queues one message (non-blocking). Fails while disconnected: callers count it.
  Status publish(const std::string& topic, std::span<const std::uint8_t> payload, int qos, bool retain);
  // Adds a filter to the subscription set (kept across reconnects) and subscribes now if connected.
  Status subscribe(const std::string& filter, int qos);
  // Removes a filter from the set and unsubscribes now if connected.
  Status unsubscribe(const std::string& filter);

  bool connected() const { return connected_.load(std::memory_order_relaxed); }
  std::vector<std::string> filters() const;
  // Bumped on every change of connection state or subscription set: time to publish them again.
  std::uint64_t version() const { return version_.load(std::memory_order_relaxed); }
  // Successful connections after the first one.
  std::uint64_t reconnects() const { return reconnects_.load(std::memory_order_relaxed); }
  const std::string& broker() const { return options_.broker; }

 private:
  enum class Link : std::uint8_t { Disconnected, Connecting, Connected };
  struct Filter {
    std::string filter;
    int qos = 0;
  };
  // Context of one subscribe/unsubscribe call, alive until paho answers (or the client dies).
  struct Request {
    MqttClient* client;
    std::vector<std::string> filters;
    bool subscribe;
  };

  MqttClient(const MqttOptions& options, std::string client_id, MessageCallback on_message);
  Status open();
  void supervise();
  int start_connect();
  void schedule_retry(const std::string& why, bool lost);
  Status send_requests(const std::vector<Filter>& filters, bool subscribe);
  void finish_request(Request* request, const std::vector<bool>& refused, int code, const char* message);

  // paho callbacks (C linkage targets): each catches everything.
  static int on_message_arrived(void* context, char* topic, int topic_len, MQTTAsync_message* message);
  static void on_connection_lost(void* context, char* cause);
  static void on_connect_success(void* context, MQTTAsync_successData* response);
  static void on_connect_failure(void* context, MQTTAsync_failureData* response);
  static void on_request_success(void* context, MQTTAsync_successData* response);
  static void on_request_failure(void* context, MQTTAsync_failureData* response);

  MqttOptions options_;
  std::string client_id_;
  MessageCallback on_message_;
  MQTTAsync handle_ = nullptr;
  MQTTAsync_SSLOptions ssl_ = MQTTAsync_SSLOptions_initializer;
  MQTTAsync_connectOptions connect_ = MQTTAsync_connectOptions_initializer;

  mutable std::mutex mutex_;  // link state, backoff, filters
  std::condition_variable wake_;
  Link link_ = Link::Disconnected;
  std::chrono::steady_clock::time_point next_attempt_{};
  Backoff backoff_;
  bool ever_connected_ = false;
  bool retry_logged_ = false;  // the current outage was logged already
  bool stop_ = false;
  std::vector<Filter> filters_;

  std::mutex requests_mutex_;
  std::map<const Request*, std::unique_ptr<Request>> requests_;

  std::atomic<bool> connected_{false};
  std::atomic<bool> closing_{false};
  std::atomic<std::uint64_t> version_{1};
  std::atomic<std::uint64_t> reconnects_{0};
  std::thread supervisor_;
};

}  // namespace slam::gateway
