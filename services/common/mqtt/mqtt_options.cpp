// Validation of ConnectionOptions.
#include "common/mqtt/mqtt_options.hpp"

#include <cmath>
#include <fstream>

#include "common/core/service_options.hpp"

namespace slam::mqtt {

namespace {

bool starts_with(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

Status readable(const char* key, const std::string& path) {
  if (path.empty()) return Status::ok();
  std::ifstream f(path);
  if (!f) return Error{std::string(key) + ": cannot read '" + path + "'"};
  return Status::ok();
}

}  // namespace

bool uses_tls(const std::string& broker) {
  return starts_with(broker, "ssl://") || starts_with(broker, "mqtts://");
}

std::string shared_filter(std::string_view group, std::string_view filter) {
  std::string shared = "$share/";
  shared += group;
  shared += '/';
  shared += filter;
  return shared;
}

Status validate_share_group(std::string_view group) {
  if (group.empty()) return Error{"share-group is empty"};
  if (group.find_first_of("/+#") != std::string_view::npos) {
    return Error{"share-group '" + std::string(group) + "' must not contain '/', '+' or '#'"};
  }
  return Status::ok();
}

Status validate(const ConnectionOptions& m) {
  const bool tls = uses_tls(m.broker);
  const bool known_scheme = tls || starts_with(m.broker, "tcp://") || starts_with(m.broker, "mqtt://");
  if (!known_scheme || m.broker.find("://") + 3 >= m.broker.size()) {
    return Error{"broker '" + m.broker + "' must look like tcp://host:port, mqtt://, ssl:// or mqtts://"};
  }
  if (m.qos < 0 || m.qos > 2) return Error{"qos must be 0, 1 or 2, not " + std::to_string(m.qos)};
  if (m.persistent_session && m.client_id.empty()) {
    return Error{"persistent-session needs a fixed client-id (the broker keeps the session under that id)"};
  }
  if (m.client_id.size() > 65535) return Error{"client-id is longer than 65535 bytes"};
  if (!m.password.empty() && m.username.empty()) return Error{"password is set but username is not"};
  const bool tls_files = !m.tls_ca_file.empty() || !m.tls_cert_file.empty() || !m.tls_key_file.empty();
  if (tls_files && !tls)
    return Error{"tls-* files are set but broker '" + m.broker + "' is not ssl:// or mqtts://"};
  if (!m.tls_key_file.empty() && m.tls_cert_file.empty())
    return Error{"tls-key-file is set but tls-cert-file is not"};
  if (auto s = readable("tls-ca-file", m.tls_ca_file); !s) return s;
  if (auto s = readable("tls-cert-file", m.tls_cert_file); !s) return s;
  if (auto s = readable("tls-key-file", m.tls_key_file); !s) return s;
  if (m.keepalive_s < 1 || m.keepalive_s > 3600) return Error{"keepalive-s must be between 1 and 3600"};
  if (m.connect_timeout_s < 1 || m.connect_timeout_s > 300)
    return Error{"connect-timeout-s must be between 1 and 300"};
  if (auto s = check_seconds("reconnect-min-s", m.reconnect_min_s, 0.01, 60.0); !s) return s;
  if (auto s = check_seconds("reconnect-max-s", m.reconnect_max_s, m.reconnect_min_s, 3600.0); !s) return s;
  for (const std::string& filter : m.subscriptions) {
    if (filter.empty()) return Error{"subscribe: a filter is empty"};
  }
  if (m.will && (m.will->topic.empty() || m.will->qos < 0 || m.will->qos > 2)) {
    return Error{"will needs a topic and a qos of 0, 1 or 2"};
  }
  if (m.max_buffered_messages < 1) return Error{"max-buffered-messages must be at least 1"};
  return Status::ok();
}

}  // namespace slam::mqtt
