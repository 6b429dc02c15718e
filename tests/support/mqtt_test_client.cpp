#include "mqtt_test_client.hpp"

#include <stdexcept>
#include <utility>

namespace slam::testkit {

MqttTestClient::MqttTestClient(int port, const std::string& client_id)
    : MqttTestClient("tcp://127.0.0.1:" + std::to_string(port), client_id) {}

MqttTestClient::MqttTestClient(const std::string& url, const std::string& client_id, std::string ca_file)
    : ca_file_(std::move(ca_file)) {
  if (MQTTClient_create(&client_, url.c_str(), client_id.c_str(), MQTTCLIENT_PERSISTENCE_NONE, nullptr) !=
      MQTTCLIENT_SUCCESS)
    throw std::runtime_error("MQTTClient_create failed for " + client_id);
  MQTTClient_setCallbacks(client_, this, nullptr, &MqttTestClient::arrived, nullptr);
}

MqttTestClient::~MqttTestClient() {
  if (MQTTClient_isConnected(client_)) MQTTClient_disconnect(client_, 100);
  MQTTClient_destroy(&client_);
}

int MqttTestClient::connect(const std::string& user, const std::string& password) {
  MQTTClient_connectOptions options = MQTTClient_connectOptions_initializer;
  options.MQTTVersion = MQTTVERSION_3_1_1;
  options.cleansession = 1;
  options.keepAliveInterval = 10;
  options.connectTimeout = 2;
  if (!user.empty()) options.username = user.c_str();
  if (!password.empty()) options.password = password.c_str();
  MQTTClient_SSLOptions ssl = MQTTClient_SSLOptions_initializer;
  if (!ca_file_.empty()) {
    ssl.trustStore = ca_file_.c_str();
    ssl.enableServerCertAuth = 1;
    if (!cert_file_.empty()) ssl.keyStore = cert_file_.c_str();
    if (!key_file_.empty()) ssl.privateKey = key_file_.c_str();
    options.ssl = &ssl;
  }
  return MQTTClient_connect(client_, &options);
}

bool MqttTestClient::connected() const {
  return MQTTClient_isConnected(client_) != 0;
}

bool MqttTestClient::subscribe(const std::string& filter, int qos) {
  return MQTTClient_subscribe(client_, filter.c_str(), qos) == MQTTCLIENT_SUCCESS;
}

bool MqttTestClient::publish(const std::string& topic, std::string_view payload, int qos) {
  MQTTClient_deliveryToken token = 0;
  // paho copies the payload; the cast only satisfies its non-const signature.
  if (MQTTClient_publish(client_, topic.c_str(), static_cast<int>(payload.size()),
                         const_cast<char*>(payload.data()), qos, 0, &token) != MQTTCLIENT_SUCCESS)
    return false;
  return qos == 0 || MQTTClient_waitForCompletion(client_, token, 2000) == MQTTCLIENT_SUCCESS;
}

bool MqttTestClient::publish(const std::string& topic, std::span<const uint8_t> payload, int qos) {
  return publish(topic, std::string_view(reinterpret_cast<const char*>(payload.data()), payload.size()), qos);
}

std::optional<MqttMessage> MqttTestClient::last(const std::string& topic) const {
  return inbox_.last([&](const MqttMessage& m) { return m.topic == topic; });
}

std::optional<MqttMessage> MqttTestClient::wait_for(const std::string& topic,
                                                    std::chrono::milliseconds timeout) const {
  return inbox_.wait_for([&](const MqttMessage& m) { return m.topic == topic; }, timeout);
}

std::optional<MqttMessage> MqttTestClient::next(std::chrono::milliseconds timeout) {
  if (!inbox_.wait_size(next_index_ + 1, timeout)) return std::nullopt;
  return inbox_.items()[next_index_++];
}

int MqttTestClient::arrived(void* self, char* topic, int topic_len, MQTTClient_message* message) {
  try {
    static_cast<MqttTestClient*>(self)->inbox_.push(MqttMessage{
        topic_len > 0 ? std::string(topic, static_cast<size_t>(topic_len)) : std::string(topic),
        std::string(static_cast<const char*>(message->payload), static_cast<size_t>(message->payloadlen)),
        std::chrono::steady_clock::now()});
  } catch (...) {
    // Out of memory on paho's thread: the message is lost, the waiting test times out and fails.
  }
  MQTTClient_freeMessage(&message);
  MQTTClient_free(topic);
  return 1;
}

}  // namespace slam::testkit
