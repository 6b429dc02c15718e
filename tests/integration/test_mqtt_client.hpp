#pragma once
// A robot or operator on the broker for integration tests: synchronous paho, every arriving message
// recorded. Plain tcp:// URLs work with paho-mqtt3c; ssl:// URLs need the test linked to
// paho-mqtt3cs and a CA file.
#include <MQTTClient.h>
#include <gtest/gtest.h>

#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace slam::testkit {

struct MqttMessage {
  std::string topic;
  std::string payload;
};

class TestMqttClient {
 public:
  TestMqttClient(const std::string& url, const std::string& client_id) {
    EXPECT_EQ(
        MQTTClient_create(&client_, url.c_str(), client_id.c_str(), MQTTCLIENT_PERSISTENCE_NONE, nullptr),
        MQTTCLIENT_SUCCESS);
    EXPECT_EQ(MQTTClient_setCallbacks(client_, this, nullptr, &TestMqttClient::arrived, nullptr),
              MQTTCLIENT_SUCCESS);
  }
  ~TestMqttClient() {
    if (MQTTClient_isConnected(client_)) MQTTClient_disconnect(client_, 100);
    MQTTClient_destroy(&client_);
  }
  TestMqttClient(const TestMqttClient&) = delete;
  TestMqttClient& operator=(const TestMqttClient&) = delete;

  // Connects with a clean session; `ca_file` non-empty verifies the broker's certificate with it.
  bool connect(const std::string& ca_file = {}) {
    MQTTClient_connectOptions options = MQTTClient_connectOptions_initializer;
    MQTTClient_SSLOptions ssl = MQTTClient_SSLOptions_initializer;
    options.cleansession = 1;
    options.keepAliveInterval = 10;
    if (!ca_file.empty()) {
      ssl.trustStore = ca_file.c_str();
      ssl.enableServerCertAuth = 1;
      options.ssl = &ssl;
    }
    return MQTTClient_connect(client_, &options) == MQTTCLIENT_SUCCESS;
  }
  bool subscribe(const std::string& filter) {
    return MQTTClient_subscribe(client_, filter.c_str(), 1) == MQTTCLIENT_SUCCESS;
  }
  // QoS 1, waits for the broker's acknowledgement.
  bool publish(const std::string& topic, const std::string& payload) {
    MQTTClient_deliveryToken token = 0;
    if (MQTTClient_publish(client_, topic.c_str(), static_cast<int>(payload.size()), payload.data(), 1, 0,
                           &token) != MQTTCLIENT_SUCCESS)
      return false;
    return MQTTClient_waitForCompletion(client_, token, 5000) == MQTTCLIENT_SUCCESS;
  }
  std::vector<MqttMessage> messages() {
    std::lock_guard lock(mutex_);
    return messages_;
  }

 private:
  static int arrived(void* context, char* topic, int topic_len, MQTTClient_message* m) {
    auto* self = static_cast<TestMqttClient*>(context);
    MqttMessage msg{topic_len > 0 ? std::string(topic, static_cast<size_t>(topic_len)) : std::string(topic),
                    std::string(static_cast<const char*>(m->payload), static_cast<size_t>(m->payloadlen))};
    {
      std::lock_guard lock(self->mutex_);
      self->messages_.push_back(std::move(msg));
    }
    MQTTClient_freeMessage(&m);
    MQTTClient_free(topic);
    return 1;
  }

  MQTTClient client_ = nullptr;
  std::mutex mutex_;
  std::vector<MqttMessage> messages_;
};

}  // namespace slam::testkit
