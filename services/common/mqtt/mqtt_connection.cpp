// Connection: paho MQTTAsync with our own reconnection (the first connection and later ones follow
// the same backoff), a subscription set replayed on every new session, and guarded callbacks.
#include "common/mqtt/mqtt_connection.hpp"

#include <MQTTAsync.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <thread>
#include <utility>

#include "common/core/guarded_callback.hpp"
#include "common/core/log.hpp"

namespace slam::mqtt {

namespace {

constexpr int kDisconnectTimeoutMs = 200;
constexpr auto kDisconnectWait = std::chrono::seconds(1);
// SUBACK's granted QoS for a filter the broker refused.
constexpr int kRefused = 0x80;

// One limiter for every connection of the process: a broker restart under a fleet of robot
// connections logs a few lines, not one per robot.
RateLimitedLog& rate_limited_log() {
  static RateLimitedLog log{std::chrono::seconds(5)};
  return log;
}

std::string failure_text(const MQTTAsync_failureData* response) {
  if (!response) return "no details from the client library";
  std::string text = response->message ? response->message : MQTTAsync_strerror(response->code);
  return text + " (code " + std::to_string(response->code) + ")";
}

std::chrono::milliseconds to_ms(double seconds) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(seconds * 1000.0));
}

std::string quoted_list(const std::vector<std::string>& items) {
  std::string list;
  for (const std::string& item : items) list += (list.empty() ? "'" : ", '") + item + "'";
  return list;
}

}  // namespace

// paho's C callbacks: each runs its body inside guarded_callback and frees what paho hands over.
struct Connection::Paho {
  static int message_arrived(void* context, char* topic, int topic_len, MQTTAsync_message* message) {
    auto* self = static_cast<Connection*>(context);
    guarded_callback("MQTT message", [&] {
      if (self->closing_.load(std::memory_order_acquire) || !self->callbacks_.message) return;
      const size_t length = topic_len > 0 ? static_cast<size_t>(topic_len) : std::strlen(topic);
      const auto* bytes = static_cast<const std::uint8_t*>(message->payload);
      self->callbacks_.message(
          std::string_view(topic, length),
          std::span<const std::uint8_t>(bytes, static_cast<size_t>(std::max(message->payloadlen, 0))));
    });
    MQTTAsync_freeMessage(&message);
    MQTTAsync_free(topic);
    return 1;  // handled: paho must not deliver it again
  }

  static void connection_lost(void* context, char* cause) {
    auto* self = static_cast<Connection*>(context);
    guarded_callback("MQTT connection-lost", [&] {
      if (self->closing_.load(std::memory_order_acquire)) return;
      const std::string why = cause ? cause : "the broker closed the connection or stopped answering";
      self->schedule_retry(why, true);
      if (self->callbacks_.lost) self->callbacks_.lost(why);
    });
    if (cause) MQTTAsync_free(cause);
  }

  static void delivered(void* context, MQTTAsync_token token) {
    auto* self = static_cast<Connection*>(context);
    guarded_callback("MQTT delivery", [&] {
      if (self->callbacks_.delivered) self->callbacks_.delivered(token);
    });
  }

  static void connect_success(void* context, MQTTAsync_successData* response) {
    auto* self = static_cast<Connection*>(context);
    guarded_callback("MQTT connect-success",
                     [&] { self->on_session(response != nullptr && response->alt.connect.sessionPresent); });
  }

  static void connect_failure(void* context, MQTTAsync_failureData* response) {
    auto* self = static_cast<Connection*>(context);
    guarded_callback("MQTT connect-failure", [&] {
      if (self->closing_.load(std::memory_order_acquire)) return;  // cut short by our own disconnect
      const std::string why = failure_text(response);
      self->schedule_retry(why, false);
      if (self->callbacks_.connect_failed) self->callbacks_.connect_failed(why);
    });
  }

  static void disconnect_done(void* context) {
    static_cast<Connection*>(context)->disconnect_done_.store(true, std::memory_order_release);
  }
  static void disconnect_success(void* context, MQTTAsync_successData* /*response*/) {
    disconnect_done(context);
  }
  static void disconnect_failure(void* context, MQTTAsync_failureData* /*response*/) {
    disconnect_done(context);
  }

  static void request_success(void* context, MQTTAsync_successData* response) {
    auto* request = static_cast<Request*>(context);
    guarded_callback("MQTT subscribe", [&] {
      // SUBACK carries the granted QoS per filter (one value, or a list for several).
      const size_t n = request->filters.size();
      std::vector<bool> refused(n, false);
      if (request->subscribe && response) {
        for (size_t i = 0; i < n; ++i) {
          const int granted =
              n == 1 ? response->alt.qos : (response->alt.qosList ? response->alt.qosList[i] : 0);
          refused[i] = granted == kRefused;
        }
      }
      request->connection->finish_request(request, refused, kRefused, "filter refused");
    });
  }

  static void request_failure(void* context, MQTTAsync_failureData* response) {
    auto* request = static_cast<Request*>(context);
    guarded_callback("MQTT subscribe", [&] {
      request->connection->finish_request(request, std::vector<bool>(request->filters.size(), true),
                                          response ? response->code : -1,
                                          response ? response->message : nullptr);
    });
  }
};

Connection::Connection(ConnectionOptions options, Callbacks callbacks)
    : options_(std::move(options)),
      callbacks_(std::move(callbacks)),
      backoff_(to_ms(options_.reconnect_min_s), to_ms(options_.reconnect_max_s)) {
  for (const std::string& f : options_.subscriptions) filters_.push_back({f, options_.qos});
}

Result<std::unique_ptr<Connection>> Connection::create(ConnectionOptions options, Callbacks callbacks) {
  if (auto s = validate(options); !s) return Error{"MQTT options: " + s.message()};
  if (options.client_id.empty()) return Error{"MQTT options: client-id is empty"};
  std::unique_ptr<Connection> connection(new Connection(std::move(options), std::move(callbacks)));
  SLAM_TRY(connection->open());
  {
    std::lock_guard lock(connection->mutex_);
    connection->link_ = Link::Connecting;
  }
  connection->start_connect();
  return connection;
}

Status Connection::open() {
  MQTTAsync_createOptions create = MQTTAsync_createOptions_initializer;
  create.sendWhileDisconnected = 0;  // a report or command is stale by the time we reconnect
  create.maxBufferedMessages = options_.max_buffered_messages;
  MQTTAsync handle = nullptr;
  int rc = MQTTAsync_createWithOptions(&handle, options_.broker.c_str(), options_.client_id.c_str(),
                                       MQTTCLIENT_PERSISTENCE_NONE, nullptr, &create);
  if (rc != MQTTASYNC_SUCCESS) {
    return Error{"MQTT client '" + options_.client_id + "' for " + options_.broker + ": " +
                 MQTTAsync_strerror(rc)};
  }
  handle_ = handle;
  rc = MQTTAsync_setCallbacks(handle_, this, &Paho::connection_lost, &Paho::message_arrived,
                              callbacks_.delivered ? &Paho::delivered : nullptr);
  if (rc != MQTTASYNC_SUCCESS) return Error{std::string("MQTT callbacks: ") + MQTTAsync_strerror(rc)};
  return Status::ok();
}

Connection::~Connection() {
  if (handle_ == nullptr) return;
  begin_disconnect();
  const auto deadline = Clock::now() + kDisconnectWait;
  while (!disconnect_done_.load(std::memory_order_acquire) && Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  MQTTAsync_destroy(&handle_);
}

void Connection::begin_disconnect() {
  if (closing_.exchange(true)) return;
  {
    std::lock_guard lock(mutex_);
    link_ = Link::Closing;
  }
  MQTTAsync_disconnectOptions disconnect = MQTTAsync_disconnectOptions_initializer;
  disconnect.timeout = kDisconnectTimeoutMs;
  disconnect.onSuccess = &Paho::disconnect_success;
  disconnect.onFailure = &Paho::disconnect_failure;
  disconnect.context = this;
  if (MQTTAsync_disconnect(handle_, &disconnect) != MQTTASYNC_SUCCESS) disconnect_done_.store(true);
}

void Connection::poll(Clock::time_point now) {
  {
    std::lock_guard lock(mutex_);
    if (link_ != Link::Disconnected || now < next_attempt_) return;
    link_ = Link::Connecting;
  }
  start_connect();
}

Connection::Clock::time_point Connection::next_attempt() const {
  std::lock_guard lock(mutex_);
  return link_ == Link::Disconnected ? next_attempt_ : Clock::time_point::max();
}

void Connection::start_connect() {
  // paho copies these settings (and the strings they point to) into the client at connect time.
  MQTTAsync_connectOptions connect = MQTTAsync_connectOptions_initializer;
  connect.keepAliveInterval = options_.keepalive_s;
  connect.cleansession = options_.persistent_session ? 0 : 1;
  connect.connectTimeout = options_.connect_timeout_s;
  connect.automaticReconnect = 0;  // poll() reconnects, with the same backoff from the start
  connect.onSuccess = &Paho::connect_success;
  connect.onFailure = &Paho::connect_failure;
  connect.context = this;
  if (!options_.username.empty()) connect.username = options_.username.c_str();
  if (!options_.password.empty()) connect.password = options_.password.c_str();
  MQTTAsync_willOptions will = MQTTAsync_willOptions_initializer;
  if (options_.will) {
    will.topicName = options_.will->topic.c_str();
    will.message = options_.will->payload.c_str();
    will.qos = options_.will->qos;
    will.retained = options_.will->retained ? 1 : 0;
    connect.will = &will;
  }
  MQTTAsync_SSLOptions ssl = MQTTAsync_SSLOptions_initializer;
  if (uses_tls(options_.broker)) {
    ssl.trustStore = options_.tls_ca_file.empty() ? nullptr : options_.tls_ca_file.c_str();
    ssl.keyStore = options_.tls_cert_file.empty() ? nullptr : options_.tls_cert_file.c_str();
    ssl.privateKey = options_.tls_key_file.empty() ? nullptr : options_.tls_key_file.c_str();
    ssl.enableServerCertAuth = 1;
    ssl.verify = 1;  // the certificate must name the host we connect to
    connect.ssl = &ssl;
  }
  spdlog::debug("MQTT connecting to {} as '{}'", options_.broker, options_.client_id);
  const int rc = MQTTAsync_connect(handle_, &connect);
  if (rc != MQTTASYNC_SUCCESS) {
    const std::string why = std::string("connect: ") + MQTTAsync_strerror(rc);
    schedule_retry(why, false);
    guarded_callback("MQTT connect-failure", [&] {
      if (callbacks_.connect_failed) callbacks_.connect_failed(why);
    });
  }
}

void Connection::schedule_retry(const std::string& why, bool lost) {
  std::chrono::milliseconds delay{};
  bool first = false;
  {
    std::lock_guard lock(mutex_);
    if (link_ == Link::Closing) return;
    link_ = Link::Disconnected;
    delay = backoff_.next();
    next_attempt_ = Clock::now() + delay;
    first = lost || !outage_logged_;
    outage_logged_ = true;
  }
  if (lost) {
    connected_.store(false, std::memory_order_release);
    version_.fetch_add(1);
    rate_limited_log().warn(
        "lost", "MQTT connection of '{}' to {} lost: {}; reconnecting (backoff {} ms, up to {} s)",
        options_.client_id, options_.broker, why, delay.count(), options_.reconnect_max_s);
  } else if (first) {
    rate_limited_log().warn("connect", "MQTT '{}' cannot connect to {}: {}; retrying with backoff up to {} s",
                            options_.client_id, options_.broker, why, options_.reconnect_max_s);
  } else {
    spdlog::debug("MQTT connect of '{}' to {} failed again: {}; next attempt in {} ms", options_.client_id,
                  options_.broker, why, delay.count());
  }
}

void Connection::on_session(bool session_present) {
  std::vector<Filter> filters;
  std::uint32_t failures = 0;
  {
    std::lock_guard lock(mutex_);
    if (link_ == Link::Closing) return;
    link_ = Link::Connected;
    failures = backoff_.failures();
    backoff_.reset();
    outage_logged_ = false;
    filters = filters_;
  }
  const bool reconnect = connects_.fetch_add(1) > 0;
  connected_.store(true, std::memory_order_release);
  version_.fetch_add(1);
  if (const auto tail = rate_limited_log().admit("connected")) {
    spdlog::info("MQTT connected to {} as '{}'{}{}{}", options_.broker, options_.client_id,
                 reconnect ? " (reconnected)" : "",
                 failures > 0 ? " after " + std::to_string(failures) + " failed attempt(s)" : std::string(),
                 *tail);
  }
  // A clean session starts with no subscriptions; a persistent one that the broker kept has them.
  if (!(session_present && options_.persistent_session)) {
    if (auto s = send_requests(filters, true); !s) spdlog::warn("MQTT {}", s.message());
  }
  if (callbacks_.connected) callbacks_.connected(reconnect);
}

Status Connection::publish(const std::string& topic, std::span<const std::uint8_t> payload, int qos,
                           bool retain) {
  if (!connected()) return Error{"publish to '" + topic + "': not connected"};
  if (payload.size() > static_cast<size_t>(std::numeric_limits<int>::max())) {
    return Error{"publish to '" + topic + "': payload too large"};
  }
  MQTTAsync_message message = MQTTAsync_message_initializer;
  // paho copies the payload before returning; it never writes through this pointer.
  message.payload = const_cast<std::uint8_t*>(payload.data());
  message.payloadlen = static_cast<int>(payload.size());
  message.qos = qos;
  message.retained = retain ? 1 : 0;
  MQTTAsync_responseOptions response = MQTTAsync_responseOptions_initializer;
  const int rc = MQTTAsync_sendMessage(handle_, topic.c_str(), &message, &response);
  if (rc != MQTTASYNC_SUCCESS) return Error{"publish to '" + topic + "': " + MQTTAsync_strerror(rc)};
  return Status::ok();
}

Status Connection::subscribe(const std::string& filter, int qos) {
  bool now = false;
  {
    std::lock_guard lock(mutex_);
    auto it =
        std::find_if(filters_.begin(), filters_.end(), [&](const Filter& f) { return f.filter == filter; });
    if (it != filters_.end()) {
      it->qos = qos;
    } else {
      filters_.push_back({filter, qos});
    }
    now = link_ == Link::Connected;
  }
  version_.fetch_add(1);
  if (!now) return Status::ok();  // sent with the others when the connection is back
  return send_requests({{filter, qos}}, true);
}

Status Connection::unsubscribe(const std::string& filter) {
  bool now = false;
  {
    std::lock_guard lock(mutex_);
    auto it =
        std::find_if(filters_.begin(), filters_.end(), [&](const Filter& f) { return f.filter == filter; });
    if (it == filters_.end()) return Error{"not subscribed to '" + filter + "'"};
    filters_.erase(it);
    now = link_ == Link::Connected;
  }
  version_.fetch_add(1);
  if (!now) return Status::ok();
  return send_requests({{filter, 0}}, false);
}

std::vector<std::string> Connection::filters() const {
  std::lock_guard lock(mutex_);
  std::vector<std::string> out;
  out.reserve(filters_.size());
  for (const Filter& f : filters_) out.push_back(f.filter);
  return out;
}

Status Connection::send_requests(const std::vector<Filter>& filters, bool subscribe) {
  if (filters.empty()) return Status::ok();
  auto owned = std::make_unique<Request>(Request{this, {}, subscribe});
  std::vector<int> qos;
  for (const Filter& f : filters) {
    owned->filters.push_back(f.filter);
    qos.push_back(f.qos);
  }
  std::vector<char*> names;
  for (std::string& f : owned->filters) names.push_back(f.data());
  Request* request = owned.get();
  {
    std::lock_guard lock(requests_mutex_);
    requests_.emplace(request, std::move(owned));
  }
  MQTTAsync_responseOptions response = MQTTAsync_responseOptions_initializer;
  response.onSuccess = &Paho::request_success;
  response.onFailure = &Paho::request_failure;
  response.context = request;
  const int count = static_cast<int>(names.size());
  const int rc = subscribe ? MQTTAsync_subscribeMany(handle_, count, names.data(), qos.data(), &response)
                           : MQTTAsync_unsubscribeMany(handle_, count, names.data(), &response);
  if (rc == MQTTASYNC_SUCCESS) return Status::ok();
  const std::string list = quoted_list(request->filters);
  {
    std::lock_guard lock(requests_mutex_);
    requests_.erase(request);
  }
  return Error{std::string(subscribe ? "subscribe " : "unsubscribe ") + list + ": " + MQTTAsync_strerror(rc)};
}

void Connection::finish_request(Request* request, const std::vector<bool>& refused, int code,
                                const char* message) {
  std::vector<std::string> accepted_filters;
  std::vector<std::string> refused_filters;
  for (size_t i = 0; i < request->filters.size(); ++i) {
    (refused[i] ? refused_filters : accepted_filters).push_back(request->filters[i]);
  }
  if (!accepted_filters.empty()) {
    if (const auto tail = rate_limited_log().admit("subscribed")) {
      spdlog::info("MQTT '{}' {} {}{}", options_.client_id,
                   request->subscribe ? "subscribed to" : "unsubscribed from", quoted_list(accepted_filters),
                   *tail);
    }
  }
  if (!refused_filters.empty()) {
    rate_limited_log().warn("refused", "MQTT broker refused '{}' to {} {}: {} (code {})", options_.client_id,
                            request->subscribe ? "subscribe" : "unsubscribe", quoted_list(refused_filters),
                            message ? message : MQTTAsync_strerror(code), code);
  }
  std::lock_guard lock(requests_mutex_);
  requests_.erase(request);
}

}  // namespace slam::mqtt
