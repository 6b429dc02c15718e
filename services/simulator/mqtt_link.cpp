// paho async wiring. Callbacks run on paho's threads: they only flip atomics, subscribe, or hand
// the message to the owner's handler, and never let an exception out.
#include "simulator/mqtt_link.hpp"

#include <fmt/format.h>

#include <cstring>
#include <thread>

#include "common/core/counters.hpp"
#include "common/core/log.hpp"

namespace slam::sim {
namespace {

constexpr int kKeepAliveS = 10;
constexpr int kMinRetryS = 1;
constexpr int kMaxRetryS = 4;
constexpr int kDisconnectTimeoutMs = 200;
constexpr auto kDisconnectWait = std::chrono::milliseconds(1000);
// QoS 0 publishes queue inside paho while the socket drains; this bounds that queue.
constexpr int kMaxBufferedMessages = 100'000;

RateLimiter& link_log_limiter() {
  static RateLimiter limiter{std::chrono::seconds(5)};
  return limiter;
}

}  // namespace

Result<std::unique_ptr<MqttLink>> MqttLink::create(MqttLinkOptions options, MessageHandler handler,
                                                   MqttLinkCounters counters) {
  std::unique_ptr<MqttLink> link(new MqttLink());
  link->options_ = std::move(options);
  link->handler_ = std::move(handler);
  link->counters_ = counters;
  MQTTAsync_createOptions create = MQTTAsync_createOptions_initializer;
  create.sendWhileDisconnected = 0;
  create.maxBufferedMessages = kMaxBufferedMessages;
  int rc = MQTTAsync_createWithOptions(&link->client_, link->options_.broker.c_str(),
                                       link->options_.client_id.c_str(), MQTTCLIENT_PERSISTENCE_NONE, nullptr,
                                       &create);
  if (rc != MQTTASYNC_SUCCESS)
    return Error{fmt::format("MQTT client '{}' for {}: {}", link->options_.client_id, link->options_.broker,
                             MQTTAsync_strerror(rc))};
  rc = MQTTAsync_setCallbacks(link->client_, link.get(), &MqttLink::on_connection_lost, &MqttLink::on_message,
                              nullptr);
  if (rc == MQTTASYNC_SUCCESS)
    rc = MQTTAsync_setConnected(link->client_, link.get(), &MqttLink::on_connected);
  if (rc != MQTTASYNC_SUCCESS) return Error{fmt::format("MQTT callbacks: {}", MQTTAsync_strerror(rc))};
  if (!link->start_connect()) link->connect_failed_ = true;
  return link;
}

MqttLink::~MqttLink() {
  if (client_ == nullptr) return;
  if (!disconnecting_) begin_disconnect();
  const auto deadline = std::chrono::steady_clock::now() + kDisconnectWait;
  while (!disconnect_done_.load(std::memory_order_acquire) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  MQTTAsync_destroy(&client_);
  set_connected(false);
}

bool MqttLink::start_connect() {
  MQTTAsync_connectOptions connect = MQTTAsync_connectOptions_initializer;
  connect.keepAliveInterval = kKeepAliveS;
  connect.cleansession = 1;
  connect.automaticReconnect = 1;
  connect.minRetryInterval = kMinRetryS;
  connect.maxRetryInterval = kMaxRetryS;
  connect.onFailure = &MqttLink::on_connect_failure;
  connect.context = this;
  if (!options_.username.empty()) connect.username = options_.username.c_str();
  if (!options_.password.empty()) connect.password = options_.password.c_str();
  MQTTAsync_willOptions will = MQTTAsync_willOptions_initializer;
  if (options_.will) {
    // paho copies the will at connect time and reuses it for automatic reconnects.
    will.topicName = options_.will->topic.c_str();
    will.message = options_.will->payload.c_str();
    will.qos = 1;
    connect.will = &will;
  }
  const int rc = MQTTAsync_connect(client_, &connect);
  if (rc == MQTTASYNC_SUCCESS) return true;
  uint64_t dropped = 0;
  if (link_log_limiter().allow("connect", &dropped))
    spdlog::warn("MQTT connect of '{}' to {} refused: {} ({} similar lines suppressed)", options_.client_id,
                 options_.broker, MQTTAsync_strerror(rc), dropped);
  return false;
}

void MqttLink::retry_connect(std::chrono::steady_clock::time_point now) {
  if (disconnecting_ || connects_.load(std::memory_order_acquire) > 0) return;
  if (!connect_failed_.load(std::memory_order_acquire) || now < next_retry_) return;
  next_retry_ = now + std::chrono::seconds(kMinRetryS);
  connect_failed_ = false;
  if (!start_connect()) connect_failed_ = true;
}

void MqttLink::begin_disconnect() {
  disconnecting_ = true;
  MQTTAsync_disconnectOptions options = MQTTAsync_disconnectOptions_initializer;
  options.timeout = kDisconnectTimeoutMs;
  options.onSuccess = &MqttLink::on_disconnected;
  options.onFailure = &MqttLink::on_disconnect_failure;
  options.context = this;
  if (MQTTAsync_disconnect(client_, &options) != MQTTASYNC_SUCCESS) disconnect_done_ = true;
}

bool MqttLink::publish(const std::string& topic, std::span<const uint8_t> payload) {
  if (!connected()) return false;
  // paho copies the payload; its API is not const-correct.
  const int rc = MQTTAsync_send(client_, topic.c_str(), static_cast<int>(payload.size()),
                                const_cast<uint8_t*>(payload.data()), 0, 0, nullptr);
  return rc == MQTTASYNC_SUCCESS;
}

void MqttLink::set_connected(bool on) {
  if (connected_.exchange(on, std::memory_order_acq_rel) != on && counters_.connected != nullptr)
    bump(*counters_.connected, on ? 1 : -1);
}

void MqttLink::on_connected(void* context, char* /*cause*/) {
  auto* self = static_cast<MqttLink*>(context);
  if (self->connects_.fetch_add(1, std::memory_order_acq_rel) > 0 && self->counters_.reconnects != nullptr)
    bump(*self->counters_.reconnects);
  self->connect_failed_ = false;
  // Clean sessions lose subscriptions with the connection: subscribe again after every connect.
  const auto& subs = self->options_.subscriptions;
  if (!subs.empty()) {
    std::vector<char*> topics;
    std::vector<int> qos(subs.size(), 1);
    for (const auto& s : subs) topics.push_back(const_cast<char*>(s.c_str()));
    const int rc = MQTTAsync_subscribeMany(self->client_, static_cast<int>(subs.size()), topics.data(),
                                           qos.data(), nullptr);
    uint64_t dropped = 0;
    if (rc != MQTTASYNC_SUCCESS && link_log_limiter().allow("subscribe", &dropped))
      spdlog::warn("MQTT subscribe of '{}' failed: {} ({} similar lines suppressed)",
                   self->options_.client_id, MQTTAsync_strerror(rc), dropped);
  }
  self->set_connected(true);
}

void MqttLink::on_connection_lost(void* context, char* /*cause*/) {
  auto* self = static_cast<MqttLink*>(context);
  self->set_connected(false);
  uint64_t dropped = 0;
  if (link_log_limiter().allow("lost", &dropped))
    spdlog::warn("MQTT connection of '{}' to {} lost; reconnecting ({} similar lines suppressed)",
                 self->options_.client_id, self->options_.broker, dropped);
}

int MqttLink::on_message(void* context, char* topic, int topic_len, MQTTAsync_message* message) {
  auto* self = static_cast<MqttLink*>(context);
  const std::string_view name(topic, topic_len > 0 ? static_cast<size_t>(topic_len) : std::strlen(topic));
  const std::span<const uint8_t> payload(static_cast<const uint8_t*>(message->payload),
                                         static_cast<size_t>(message->payloadlen));
  try {
    self->handler_(name, payload);
  } catch (const std::exception& e) {
    spdlog::error("MQTT message handler threw: {}", e.what());
  } catch (...) {
    spdlog::error("MQTT message handler threw a non-standard exception");
  }
  MQTTAsync_freeMessage(&message);
  MQTTAsync_free(topic);
  return 1;
}

void MqttLink::on_connect_failure(void* context, MQTTAsync_failureData* data) {
  auto* self = static_cast<MqttLink*>(context);
  self->connect_failed_ = true;
  if (self->disconnecting_) return;  // a connect cut short by our own disconnect is no failure
  if (self->counters_.connect_failures != nullptr) bump(*self->counters_.connect_failures);
  uint64_t dropped = 0;
  if (link_log_limiter().allow("connect_failed", &dropped))
    spdlog::warn("MQTT connect of '{}' to {} failed: {}; retrying ({} similar lines suppressed)",
                 self->options_.client_id, self->options_.broker,
                 data != nullptr && data->message != nullptr ? data->message
                                                             : MQTTAsync_strerror(data ? data->code : -1),
                 dropped);
}

void MqttLink::on_disconnected(void* context, MQTTAsync_successData* /*data*/) {
  static_cast<MqttLink*>(context)->disconnect_done_ = true;
}

void MqttLink::on_disconnect_failure(void* context, MQTTAsync_failureData* /*data*/) {
  static_cast<MqttLink*>(context)->disconnect_done_ = true;
}

}  // namespace slam::sim
