// MQTT tab actions (see mqtt_tab.hpp).
#include "viewer/core/mqtt_tab.hpp"

#include "viewer/core/payload_text.hpp"

namespace slam::viewer {
namespace {

// The gateway takes filters with + and #; a publish topic must name one topic.
Status check_topic(const std::string& t, bool wildcards_allowed) {
  if (t.empty() || t.size() > kMaxMqttTopic) return Error{"topic must be 1..256 characters"};
  if (!wildcards_allowed && t.find_first_of("+#") != std::string::npos)
    return Error{"a publish topic cannot hold the wildcards + or #"};
  return {};
}

Result<std::vector<uint8_t>> payload_bytes(PayloadKind kind, const std::string& text) {
  switch (kind) {
    case PayloadKind::V1Pairs: {
      auto pairs = parse_pairs(text);
      if (!pairs) return pairs.error();
      return encode_v1_pairs(*pairs);
    }
    case PayloadKind::Hex:
      return parse_hex(text);
    case PayloadKind::Text:
      break;
  }
  return std::vector<uint8_t>(text.begin(), text.end());
}

void send_tracked(ViewerState& state, CommandSink& sink, const MqttRequestCommand& c, const std::string& what,
                  std::string& error, int64_t now_ns) {
  if (const uint64_t id = state.note_sent(sink.send(c), what, error))
    state.mqtt_requests.sent(id, what, now_ns);
}

}  // namespace

bool MqttLogView::shows(const MqttEntry& e) const {
  return (e.inbound ? show_inbound : show_outbound) &&
         (search.empty() || e.topic.find(search) != std::string::npos);
}

std::string MqttLogView::payload_text(const MqttEntry& e) const {
  return decoded ? decode_payload(e.topic, e.payload) : to_hex(e.payload, 96);
}

void MqttTab::subscribe(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  if (Status s = check_topic(filter, true); !s) {
    error = "subscribe: " + s.message();
    return;
  }
  send_tracked(state, sink, MqttRequestCommand{MqttRequestKind::Subscribe, filter, {}, 1, false},
               "subscribe " + filter, error, now_ns);
}

void MqttTab::unsubscribe(ViewerState& state, CommandSink& sink, const std::string& subscribed_filter,
                          int64_t now_ns) {
  if (Status s = check_topic(subscribed_filter, true); !s) {
    error = "unsubscribe: " + s.message();
    return;
  }
  send_tracked(state, sink, MqttRequestCommand{MqttRequestKind::Unsubscribe, subscribed_filter, {}, 0, false},
               "unsubscribe " + subscribed_filter, error, now_ns);
}

void MqttTab::publish(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  if (Status s = check_topic(topic, false); !s) {
    error = "publish: " + s.message();
    return;
  }
  if (qos < 0 || qos > 2) {
    error = "publish: QoS must be 0, 1 or 2";
    return;
  }
  auto bytes = payload_bytes(payload_kind, payload);
  if (!bytes) {
    error = "publish: " + bytes.message();
    return;
  }
  const std::string what = "publish " + std::to_string(bytes->size()) + " octets to " + topic;
  send_tracked(state, sink,
               MqttRequestCommand{MqttRequestKind::Publish, topic, std::move(*bytes),
                                  static_cast<uint8_t>(qos), retain},
               what, error, now_ns);
}

}  // namespace slam::viewer
