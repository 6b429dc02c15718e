#pragma once
// One MQTT connection over paho-mqtt-c's asynchronous client (TLS capable), shared by the gateway
// and the simulator's robots. It keeps a subscription set and replays it on every new session (a
// clean session forgets subscriptions), and reconnects after a failed attempt or a lost connection
// with exponential backoff (ConnectionOptions::reconnect_min_s..max_s). Attempts are started from
// the owner's loop through poll(), so a fleet of a thousand robot connections needs no thread each.
// Every paho callback runs inside slam::guarded_callback: no exception crosses back into paho.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"
#include "common/mqtt/backoff.hpp"
#include "common/mqtt/mqtt_options.hpp"

namespace slam::mqtt {

// Called on paho's threads: copy what is needed and return quickly. Exceptions are caught and logged.
struct Callbacks {
  // A session started; `reconnect` is false for the first one.
  std::function<void(bool reconnect)> connected;
  // An established session ended (not called for the owner's own disconnect).
  std::function<void(const std::string& cause)> lost;
  // A connection attempt failed; the next one follows the backoff.
  std::function<void(const std::string& reason)> connect_failed;
  // Every inbound message; `topic` and `payload` die when it returns.
  std::function<void(std::string_view topic, std::span<const std::uint8_t> payload)> message;
  // A QoS 1 or 2 publish was acknowledged by the broker (`token` from paho).
  std::function<void(int token)> delivered;
};

class Connection {
 public:
  using Clock = std::chrono::steady_clock;

  // Validates the options, creates the client and starts the first connection attempt (a broker
  // that is down is retried like one that went away). Errors: bad options, a URL paho refuses.
  static Result<std::unique_ptr<Connection>> create(ConnectionOptions options, Callbacks callbacks);
  // Disconnects cleanly (begin_disconnect, then waits up to a second) and destroys the client.
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  // Starts the next connection attempt when one is due. Call from the owner's loop.
  void poll(Clock::time_point now);
  // When poll() has an attempt to start; time_point::max() while connected or connecting.
  Clock::time_point next_attempt() const;
  // Asks for a clean disconnect (queued publishes go first) without waiting; no reconnect follows.
  // Lets an owner of many connections close them all in one round trip.
  void begin_disconnect();

  // Queues one message (non-blocking). Fails while disconnected: callers count it.
  Status publish(const std::string& topic, std::span<const std::uint8_t> payload, int qos, bool retain);
  // Adds a filter to the subscription set (kept across reconnects) and subscribes now if connected.
  Status subscribe(const std::string& filter, int qos);
  // Removes a filter from the set and unsubscribes now if connected.
  Status unsubscribe(const std::string& filter);

  bool connected() const { return connected_.load(std::memory_order_acquire); }
  std::vector<std::string> filters() const;
  // Bumped on every change of connection state or subscription set.
  std::uint64_t version() const { return version_.load(std::memory_order_acquire); }
  // Sessions started so far: a change tells the owner to resend what a fresh session needs.
  std::uint64_t connects() const { return connects_.load(std::memory_order_acquire); }
  // Sessions started after the first one.
  std::uint64_t reconnects() const {
    const std::uint64_t n = connects();
    return n > 0 ? n - 1 : 0;
  }
  const std::string& broker() const { return options_.broker; }
  const std::string& client_id() const { return options_.client_id; }

 private:
  enum class Link : std::uint8_t { Disconnected, Connecting, Connected, Closing };
  struct Filter {
    std::string filter;
    int qos = 0;
  };
  // Context of one subscribe/unsubscribe call, alive until paho answers (or the connection dies).
  struct Request {
    Connection* connection;
    std::vector<std::string> filters;
    bool subscribe;
  };
  struct Paho;  // the C callbacks, defined next to the paho calls

  Connection(ConnectionOptions options, Callbacks callbacks);
  Status open();
  void start_connect();
  void schedule_retry(const std::string& why, bool lost);
  void on_session(bool session_present);
  Status send_requests(const std::vector<Filter>& filters, bool subscribe);
  void finish_request(Request* request, const std::vector<bool>& refused, int code, const char* message);

  ConnectionOptions options_;
  Callbacks callbacks_;
  void* handle_ = nullptr;  // MQTTAsync

  mutable std::mutex mutex_;  // link state, backoff, filters
  Link link_ = Link::Disconnected;
  Clock::time_point next_attempt_{};
  Backoff backoff_;
  bool outage_logged_ = false;  // the current outage was logged already
  std::vector<Filter> filters_;

  std::mutex requests_mutex_;
  std::map<const Request*, std::unique_ptr<Request>> requests_;

  std::atomic<bool> connected_{false};
  std::atomic<bool> closing_{false};
  std::atomic<bool> disconnect_done_{false};
  std::atomic<std::uint64_t> version_{1};
  std::atomic<std::uint64_t> connects_{0};
};

}  // namespace slam::mqtt
