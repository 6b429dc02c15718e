// Bounded MQTT message log (see mqtt_log.hpp).
#include "viewer/core/mqtt_log.hpp"

#include <utility>

namespace slam::viewer {

void MqttLog::push(MqttEntry&& e) {
  ++(e.inbound ? inbound_ : outbound_);
  bytes_ += cost(e);
  entries_.push_back(std::move(e));
  while (!entries_.empty() && (entries_.size() > max_entries_ || bytes_ > max_bytes_)) {
    bytes_ -= cost(entries_.front());
    entries_.pop_front();
    ++evicted_;
  }
}

void MqttLog::clear() {
  entries_.clear();
  bytes_ = 0;
}

}  // namespace slam::viewer
