#pragma once
// MQTT topic names and subscription filters as operators give them (--subscribe, the viewer's
// MqttRequest), checked before they reach the client library: a bad one is refused with the
// reason instead of the broker dropping the connection.
#include <cstddef>
#include <string_view>

#include "common/core/result.hpp"

namespace slam::gateway {

inline constexpr std::size_t kMaxTopicBytes = 256;  // the IDL's string<256> for topics and filters

// A subscription filter (MQTT 3.1.1 §4.7): 1..256 bytes of UTF-8 without control characters;
// '+' and '#' only as a whole level, '#' only as the last one.
Status validate_filter(std::string_view filter);
// A topic to publish to: as a filter, but with no wildcard at all.
Status validate_topic_name(std::string_view topic);

}  // namespace slam::gateway
