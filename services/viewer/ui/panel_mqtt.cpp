// MQTT tab: the gateway's subscriptions (add/remove), publishing raw hex, text or a SLAM v1
// message to any topic, and the bounded in/out log with raw or decoded payloads.
#include <imgui.h>

#include <cstring>

#include "viewer/core/payload_text.hpp"
#include "viewer/ui/panels.hpp"

namespace slam::viewer {
namespace {

constexpr size_t kMaxTopic = 256;  // idl: string<256>

}  // namespace

void MqttPanel::draw(ViewerState& state, CommandSink& sink) {
  draw_subscriptions(state, sink);
  draw_publish(state, sink);
  draw_log(state);
}

void MqttPanel::draw_subscriptions(ViewerState& state, CommandSink& sink) {
  section_title("Subscriptions");
  if (!state.have_subscriptions) {
    ImGui::TextDisabled("no gateway seen yet");
  } else {
    ImGui::Text("broker %s: %s", state.subscriptions.broker.c_str(),
                state.subscriptions.connected ? "connected" : "DISCONNECTED");
    for (const auto& f : state.subscriptions.filters) {
      ImGui::PushID(f.c_str());
      if (ImGui::SmallButton("remove"))
        state.status_line = sink.send(MqttRequestCommand{MqttRequestKind::Unsubscribe, f, {}, 0, false})
                                ? "unsubscribe " + f + " sent"
                                : "unsubscribe NOT sent";
      ImGui::SameLine();
      ImGui::TextUnformatted(f.c_str());
      ImGui::PopID();
    }
  }
  ImGui::SetNextItemWidth(-90.0f);
  ImGui::InputText("##filter", filter, sizeof filter);
  ImGui::SameLine();
  if (ImGui::Button("subscribe") && std::strlen(filter) > 0)
    state.status_line = sink.send(MqttRequestCommand{MqttRequestKind::Subscribe, filter, {}, 1, false})
                            ? std::string("subscribe ") + filter + " sent"
                            : "subscribe NOT sent";
}

void MqttPanel::draw_publish(ViewerState& state, CommandSink& sink) {
  section_title("Publish");
  ImGui::InputText("topic", topic, sizeof topic);
  ImGui::RadioButton("SLAM v1 (x,y pairs)", &payload_kind, 0);
  ImGui::SameLine();
  ImGui::RadioButton("raw hex", &payload_kind, 1);
  ImGui::SameLine();
  ImGui::RadioButton("text", &payload_kind, 2);
  ImGui::InputTextMultiline("##payload", payload, sizeof payload, ImVec2(-1.0f, 48.0f));
  ImGui::SetNextItemWidth(80.0f);
  ImGui::SliderInt("QoS", &qos, 0, 2);
  ImGui::SameLine();
  ImGui::Checkbox("retain", &retain);
  ImGui::SameLine();
  if (ImGui::Button("publish")) {
    Result<std::vector<uint8_t>> bytes = std::vector<uint8_t>{};
    if (payload_kind == 0) {
      auto pairs = parse_pairs(payload);
      bytes = pairs ? encode_v1_pairs(*pairs) : Result<std::vector<uint8_t>>(Error{pairs.message()});
    } else if (payload_kind == 1) {
      bytes = parse_hex(payload);
    } else {
      bytes = std::vector<uint8_t>(payload, payload + std::strlen(payload));
    }
    const size_t topic_len = std::strlen(topic);
    if (topic_len == 0 || topic_len > kMaxTopic || std::strpbrk(topic, "+#")) {
      error = "topic must be 1..256 characters without wildcards";
    } else if (!bytes) {
      error = bytes.message();
    } else {
      error.clear();
      const uint64_t id = sink.send(
          MqttRequestCommand{MqttRequestKind::Publish, topic, *bytes, static_cast<uint8_t>(qos), retain});
      state.status_line =
          id ? "published " + std::to_string(bytes->size()) + " octets to " + topic : "publish NOT sent";
    }
  }
  if (!error.empty()) ImGui::TextColored({1, 0.4f, 0.4f, 1}, "%s", error.c_str());
}

void MqttPanel::draw_log(ViewerState& state) {
  const MqttLog& log = state.mqtt;
  section_title("Traffic");
  ImGui::Checkbox("in", &show_inbound);
  ImGui::SameLine();
  ImGui::Checkbox("out", &show_outbound);
  ImGui::SameLine();
  ImGui::Checkbox("decoded", &decoded);
  ImGui::SameLine();
  ImGui::Checkbox("autoscroll", &autoscroll);
  ImGui::SameLine();
  if (ImGui::SmallButton("clear")) state.mqtt.clear();
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::InputTextWithHint("##search", "topic contains...", search, sizeof search);
  hint("%zu kept (%zu KiB of %zu), %llu evicted, %llu in / %llu out, %llu dropped", log.size(),
       log.bytes() / 1024, log.max_bytes() / 1024, static_cast<unsigned long long>(log.evicted()),
       static_cast<unsigned long long>(log.inbound()), static_cast<unsigned long long>(log.outbound()),
       static_cast<unsigned long long>(state.mqtt_dropped));
  ImGui::BeginChild("mqtt-log", ImVec2(0, 0), true, ImGuiWindowFlags_HorizontalScrollbar);
  const bool filtered = search[0] != '\0' || !show_inbound || !show_outbound;
  auto visible = [&](const MqttEntry& e) {
    return (e.inbound ? show_inbound : show_outbound) &&
           (search[0] == '\0' || e.topic.find(search) != std::string::npos);
  };
  auto row = [&](const MqttEntry& e) {
    ImGui::TextColored(e.inbound ? ImVec4(0.5f, 0.8f, 1, 1) : ImVec4(1, 0.8f, 0.4f, 1), "%s %s [%u]",
                       e.inbound ? "<-" : "->", e.topic.c_str(), e.payload_size);
    ImGui::SameLine();
    const std::string text = decoded ? decode_payload(e.topic, e.payload) : to_hex(e.payload, 96);
    ImGui::TextUnformatted(text.c_str());
  };
  if (filtered) {
    for (size_t i = 0; i < log.size(); ++i)
      if (visible(log.at(i))) row(log.at(i));
  } else {
    // Only the rows on screen are formatted: the log can hold thousands.
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(log.size()));
    while (clipper.Step())
      for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) row(log.at(static_cast<size_t>(i)));
  }
  if (autoscroll && ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 20.0f) ImGui::SetScrollHereY(1.0f);
  ImGui::EndChild();
}

}  // namespace slam::viewer
