#pragma once
// The MQTT tab's controls and what they do, without ImGui: subscribe, unsubscribe, publish (SLAM
// v1 pairs, raw hex or text) and the log's view. Every request goes through the CommandSink and
// is tracked in ViewerState::mqtt_requests until the gateway's reply; invalid input sets `error`
// and sends nothing.
#include <cstdint>
#include <string>

#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

inline constexpr size_t kMaxMqttTopic = 256;  // idl: string<256>

enum class PayloadKind : uint8_t { V1Pairs, Hex, Text };

// Which log rows the Traffic list shows, and how.
struct MqttLogView {
  bool show_inbound = true;
  bool show_outbound = true;
  bool decoded = true;
  bool autoscroll = true;
  std::string search;  // topic contains

  bool filtered() const { return !search.empty() || !show_inbound || !show_outbound; }
  bool shows(const MqttEntry& e) const;
  // The payload column: decoded (v1 messages, text) or hex.
  std::string payload_text(const MqttEntry& e) const;
};

struct MqttTab {
  std::string filter = "v1/robot/+/adv";
  std::string topic = "v1/server/robot1/cmd";
  std::string payload;
  PayloadKind payload_kind = PayloadKind::V1Pairs;
  int qos = 0;
  bool retain = false;
  MqttLogView log;
  std::string error;  // the last refused input, shown in red

  void subscribe(ViewerState& state, CommandSink& sink, int64_t now_ns);
  void unsubscribe(ViewerState& state, CommandSink& sink, const std::string& subscribed_filter,
                   int64_t now_ns);
  void publish(ViewerState& state, CommandSink& sink, int64_t now_ns);
  static void clear_log(ViewerState& state) { state.mqtt.clear(); }
};

}  // namespace slam::viewer
