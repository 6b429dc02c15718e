// MqttClient: paho MQTTAsync with our own reconnection supervisor (so the first connection and
// later ones follow the same backoff), a subscription set replayed on every new session, and
// callbacks that swallow and log anything thrown.
#include "gateway/mqtt_client.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <limits>
#include <utility>

namespace slam::gateway {

namespace {

using Clock = std::chrono::steady_clock;

// Runs `fn` and logs whatever it throws: paho is C, and an exception unwinding into it is fatal.
template <class F>
void guarded(const char* where, F&& fn) noexcept {
  try {
    fn();
  } catch (const std::exception& e) {
    try {
      spdlog::error("MQTT {} callback failed: {}", where, e.what());
    } catch (...) {  // logging itself failed: nothing more can be done here
    }
  } catch (...) {
    try {
      spdlog::error("MQTT {} callback failed with an unknown exception", where);
    } catch (...) {  // as above
    }
  }
}

std::string failure_text(const MQTTAsync_failureData* response) {
  if (!response) return "no details from the client library";
  std::string text = response->message ? response->message : MQTTAsync_strerror(response->code);
  return text + " (code " + std::to_string(response->code) + ")";
}

std::chrono::milliseconds to_ms(double seconds) {
  return std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000.0));
}

}  // namespace

MqttClient::MqttClient(const MqttOptions& options, std::string client_id, MessageCallback on_message)
    : options_(options),
      client_id_(std::move(client_id)),
      on_message_(std::move(on_message)),
      backoff_(to_ms(options.reconnect_min_s), to_ms(options.reconnect_max_s)) {
  for (const std::string& f : options_.subscriptions) filters_.push_back({f, options_.qos});
}

Result<std::unique_ptr<MqttClient>> MqttClient::create(const MqttOptions& options, std::string client_id,
                                                       MessageCallback on_message) {
  std::unique_ptr<MqttClient> client(new MqttClient(options, std::move(client_id), std::move(on_message)));
  if (auto s = client->open(); !s) return Error{s.message()};
  return client;
}

Status MqttClient::open() {
  MQTTAsync_createOptions create = MQTTAsync_createOptions_initializer;
  create.sendWhileDisconnected = 0;  // a command for a robot is stale by the time we reconnect
  int rc = MQTTAsync_createWithOptions(&handle_, options_.broker.c_str(), client_id_.c_str(),
                                       MQTTCLIENT_PERSISTENCE_NONE, nullptr, &create);
  if (rc != MQTTASYNC_SUCCESS) {
    handle_ = nullptr;
    return Error{"MQTT client for '" + options_.broker + "': " + MQTTAsync_strerror(rc)};
  }
  rc = MQTTAsync_setCallbacks(handle_, this, &MqttClient::on_connection_lost, &MqttClient::on_message_arrived,
                              nullptr);
  if (rc != MQTTASYNC_SUCCESS) return Error{std::string("MQTT callbacks: ") + MQTTAsync_strerror(rc)};

  connect_.keepAliveInterval = options_.keepalive_s;
  connect_.cleansession = options_.persistent_session ? 0 : 1;
  connect_.connectTimeout = options_.connect_timeout_s;
  connect_.automaticReconnect = 0;  // supervise() reconnects, with the same backoff from the start
  connect_.onSuccess = &MqttClient::on_connect_success;
  connect_.onFailure = &MqttClient::on_connect_failure;
  connect_.context = this;
  if (!options_.username.empty()) connect_.username = options_.username.c_str();
  if (!options_.password.empty()) connect_.password = options_.password.c_str();
  if (uses_tls(options_.broker)) {
    ssl_.trustStore = options_.tls_ca_file.empty() ? nullptr : options_.tls_ca_file.c_str();
    ssl_.keyStore = options_.tls_cert_file.empty() ? nullptr : options_.tls_cert_file.c_str();
    ssl_.privateKey = options_.tls_key_file.empty() ? nullptr : options_.tls_key_file.c_str();
    ssl_.enableServerCertAuth = 1;
    ssl_.verify = 1;  // the certificate must name the host we connect to
    connect_.ssl = &ssl_;
  }
  supervisor_ = std::thread([this] { supervise(); });
  return Status::ok();
}

MqttClient::~MqttClient() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (supervisor_.joinable()) supervisor_.join();
  closing_.store(true);
  if (handle_) {
    if (MQTTAsync_isConnected(handle_)) {
      MQTTAsync_disconnectOptions disconnect = MQTTAsync_disconnectOptions_initializer;
      disconnect.timeout = 1000;
      if (MQTTAsync_disconnect(handle_, &disconnect) == MQTTASYNC_SUCCESS) {
        const auto deadline = Clock::now() + std::chrono::seconds(2);
        while (MQTTAsync_isConnected(handle_) && Clock::now() < deadline) {
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
      }
    }
    MQTTAsync_destroy(&handle_);
  }
}

void MqttClient::supervise() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    if (link_ != Link::Disconnected) {
      wake_.wait(lock);
      continue;
    }
    if (Clock::now() < next_attempt_) {
      wake_.wait_until(lock, next_attempt_);
      continue;
    }
    link_ = Link::Connecting;
    lock.unlock();
    const int rc = start_connect();
    if (rc != MQTTASYNC_SUCCESS) schedule_retry(std::string("connect: ") + MQTTAsync_strerror(rc), false);
    lock.lock();
  }
}

int MqttClient::start_connect() {
  spdlog::debug("MQTT connecting to {} as '{}'", options_.broker, client_id_);
  return MQTTAsync_connect(handle_, &connect_);
}

void MqttClient::schedule_retry(const std::string& why, bool lost) {
  std::chrono::milliseconds delay{};
  bool first = false;
  {
    std::lock_guard lock(mutex_);
    link_ = Link::Disconnected;
    delay = backoff_.next();
    next_attempt_ = Clock::now() + delay;
    first = lost || !retry_logged_;
    retry_logged_ = true;
  }
  wake_.notify_all();
  if (lost) {
    connected_.store(false);
    version_.fetch_add(1);
    spdlog::warn("MQTT connection to {} lost: {}; reconnecting (backoff {} ms, up to {} s)", options_.broker,
                 why, delay.count(), options_.reconnect_max_s);
  } else if (first) {
    spdlog::warn("MQTT cannot connect to {}: {}; retrying with backoff up to {} s", options_.broker, why,
                 options_.reconnect_max_s);
  } else {
    spdlog::debug("MQTT connect to {} failed again: {}; next attempt in {} ms", options_.broker, why,
                  delay.count());
  }
}

void MqttClient::on_connection_lost(void* context, char* cause) {
  auto* self = static_cast<MqttClient*>(context);
  guarded("connection-lost", [&] {
    if (self->closing_.load()) return;
    self->schedule_retry(cause ? cause : "the broker closed the connection or stopped answering", true);
  });
  if (cause) MQTTAsync_free(cause);
}

void MqttClient::on_connect_success(void* context, MQTTAsync_successData* response) {
  auto* self = static_cast<MqttClient*>(context);
  guarded("connect-success", [&] {
    const bool session_present = response && response->alt.connect.sessionPresent;
    std::vector<Filter> filters;
    bool reconnect = false;
    uint32_t failures = 0;
    {
      std::lock_guard lock(self->mutex_);
      self->link_ = Link::Connected;
      failures = self->backoff_.failures();
      self->backoff_.reset();
      self->retry_logged_ = false;
      reconnect = self->ever_connected_;
      self->ever_connected_ = true;
      filters = self->filters_;
    }
    self->connected_.store(true);
    self->version_.fetch_add(1);
    if (reconnect) self->reconnects_.fetch_add(1);
    spdlog::info("MQTT connected to {} as '{}'{}{}", self->options_.broker, self->client_id_,
                 reconnect ? " (reconnected)" : "",
                 failures > 0 ? " after " + std::to_string(failures) + " failed attempt(s)" : std::string());
    // A clean session starts with no subscriptions; a persistent one that the broker kept has them.
    if (session_present && self->options_.persistent_session) return;
    if (auto s = self->send_requests(filters, true); !s) spdlog::warn("MQTT {}", s.message());
  });
}

void MqttClient::on_connect_failure(void* context, MQTTAsync_failureData* response) {
  auto* self = static_cast<MqttClient*>(context);
  guarded("connect-failure", [&] { self->schedule_retry(failure_text(response), false); });
}

Status MqttClient::publish(const std::string& topic, std::span<const std::uint8_t> payload, int qos,
                           bool retain) {
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

Status MqttClient::subscribe(const std::string& filter, int qos) {
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

Status MqttClient::unsubscribe(const std::string& filter) {
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

std::vector<std::string> MqttClient::filters() const {
  std::lock_guard lock(mutex_);
  std::vector<std::string> out;
  out.reserve(filters_.size());
  for (const Filter& f : filters_) out.push_back(f.filter);
  return out;
}

Status MqttClient::send_requests(const std::vector<Filter>& filters, bool subscribe) {
  if (filters.empty()) return Status::ok();
  auto owned = std::make_unique<Request>(Request{this, {}, subscribe});
  std::vector<char*> names;
  std::vector<int> qos;
  for (const Filter& f : filters) owned->filters.push_back(f.filter);
  for (size_t i = 0; i < filters.size(); ++i) {
    names.push_back(owned->filters[i].data());
    qos.push_back(filters[i].qos);
  }
  Request* request = owned.get();
  {
    std::lock_guard lock(requests_mutex_);
    requests_.emplace(request, std::move(owned));
  }
  MQTTAsync_responseOptions response = MQTTAsync_responseOptions_initializer;
  response.onSuccess = &MqttClient::on_request_success;
  response.onFailure = &MqttClient::on_request_failure;
  response.context = request;
  const int count = static_cast<int>(names.size());
  const int rc = subscribe ? MQTTAsync_subscribeMany(handle_, count, names.data(), qos.data(), &response)
                           : MQTTAsync_unsubscribeMany(handle_, count, names.data(), &response);
  if (rc == MQTTASYNC_SUCCESS) return Status::ok();
  std::string joined;
  for (const std::string& f : request->filters) joined += (joined.empty() ? "'" : ", '") + f + "'";
  {
    std::lock_guard lock(requests_mutex_);
    requests_.erase(request);
  }
  return Error{std::string(subscribe ? "subscribe " : "unsubscribe ") + joined + ": " +
               MQTTAsync_strerror(rc)};
}

void MqttClient::finish_request(Request* request, const std::vector<bool>& refused, int code,
                                const char* message) {
  std::string accepted_list;
  std::string refused_list;
  for (size_t i = 0; i < request->filters.size(); ++i) {
    std::string& list = refused[i] ? refused_list : accepted_list;
    list += (list.empty() ? "'" : ", '") + request->filters[i] + "'";
  }
  if (!accepted_list.empty()) {
    spdlog::info("MQTT {} {}", request->subscribe ? "subscribed to" : "unsubscribed from", accepted_list);
  }
  if (!refused_list.empty()) {
    spdlog::warn("MQTT broker refused to {} {}: {} (code {})",
                 request->subscribe ? "subscribe" : "unsubscribe", refused_list,
                 message ? message : MQTTAsync_strerror(code), code);
  }
  std::lock_guard lock(requests_mutex_);
  requests_.erase(request);
}

void MqttClient::on_request_success(void* context, MQTTAsync_successData* response) {
  auto* request = static_cast<Request*>(context);
  guarded("subscribe", [&] {
    // SUBACK carries the granted QoS per filter (one value, or a list for several); 0x80 means
    // the broker refused that filter.
    constexpr int kRefused = 0x80;
    const size_t n = request->filters.size();
    std::vector<bool> refused(n, false);
    if (request->subscribe && response) {
      for (size_t i = 0; i < n; ++i) {
        const int granted =
            n == 1 ? response->alt.qos : (response->alt.qosList ? response->alt.qosList[i] : 0);
        refused[i] = granted == kRefused;
      }
    }
    request->client->finish_request(request, refused, kRefused, "filter refused");
  });
}

void MqttClient::on_request_failure(void* context, MQTTAsync_failureData* response) {
  auto* request = static_cast<Request*>(context);
  guarded("subscribe", [&] {
    request->client->finish_request(request, std::vector<bool>(request->filters.size(), true),
                                    response ? response->code : -1, response ? response->message : nullptr);
  });
}

int MqttClient::on_message_arrived(void* context, char* topic, int topic_len, MQTTAsync_message* message) {
  auto* self = static_cast<MqttClient*>(context);
  guarded("message", [&] {
    if (self->closing_.load(std::memory_order_relaxed)) return;
    const size_t length = topic_len > 0 ? static_cast<size_t>(topic_len) : std::strlen(topic);
    const auto* bytes = static_cast<const std::uint8_t*>(message->payload);
    self->on_message_(
        std::string_view(topic, length),
        std::span<const std::uint8_t>(bytes, static_cast<size_t>(std::max(message->payloadlen, 0))));
  });
  MQTTAsync_freeMessage(&message);
  MQTTAsync_free(topic);
  return 1;  // handled: paho must not deliver it again
}

}  // namespace slam::gateway
