#pragma once
// Settings of one MQTT connection (slam::mqtt::Connection), with defaults and one validator that
// names the bad key the way the services' flags do ("keepalive-s must be ...").
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/result.hpp"

namespace slam::mqtt {

// Published by the broker when the connection dies without a clean disconnect.
struct Will {
  std::string topic;
  std::string payload;
  int qos = 1;
  bool retained = false;
};

struct ConnectionOptions {
  std::string broker = "tcp://127.0.0.1:1883";  // tcp://, mqtt://, ssl:// or mqtts://
  std::string client_id;                        // must be set before Connection::create
  int qos = 1;                                  // of `subscriptions` (and the owner's commands)
  bool persistent_session = false;              // false: clean session, re-subscribe on reconnect
  std::string username;                         // empty: anonymous
  std::string password;
  std::string tls_ca_file;    // PEM trust store; TLS when the broker URL is ssl:// or mqtts://
  std::string tls_cert_file;  // PEM client certificate chain (mutual TLS)
  std::string tls_key_file;   // PEM private key when not inside tls_cert_file
  int keepalive_s = 20;
  int connect_timeout_s = 5;
  // Reconnection: the first retry after reconnect_min_s, doubling per failure up to reconnect_max_s.
  double reconnect_min_s = 0.25;
  double reconnect_max_s = 30.0;
  std::vector<std::string> subscriptions;  // subscribed at `qos` on every new session
  std::optional<Will> will;
  // Publishes paho may hold in its queue while the socket drains (paho's default is 100).
  int max_buffered_messages = 100;
};

// Ok, or the first bad setting with the reason ("qos must be 0, 1 or 2, not 3"). An empty
// client id is allowed here (a service may fill in a default) unless the session is persistent.
Status validate(const ConnectionOptions& options);

// True for ssl:// and mqtts:// broker URLs.
bool uses_tls(const std::string& broker);

// A shared subscription (MQTT 5 §4.8.2, also served to 3.1.1 clients by mosquitto 2 and the common
// clustered brokers): "$share/<group>/<filter>". The broker hands each matching message to one member
// of the group, round-robin in mosquitto, and delivers it under its real topic (paho-mqtt-c passes
// that topic to the message callback as it is; it does no filter matching of its own).
std::string shared_filter(std::string_view group, std::string_view filter);
// Ok, or why `group` cannot name a share group: empty, or containing '/', '+' or '#'.
Status validate_share_group(std::string_view group);

}  // namespace slam::mqtt
