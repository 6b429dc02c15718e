// MQTT tab: the gateway's subscriptions (add/remove), publishing raw hex, text or a SLAM v1
// message to any topic, the last request's reply, and the bounded in/out log with raw or decoded
// payloads. The actions are MqttTab's (core/mqtt_tab.hpp).
#include <imgui.h>
#include <imgui_stdlib.h>

#include "viewer/ui/panels.hpp"

namespace slam::viewer {
namespace {

void draw_subscriptions(MqttTab& tab, ViewerState& state, CommandSink& sink, int64_t now_ns) {
  section_title("Subscriptions");
  if (!state.have_subscriptions) {
    ImGui::TextDisabled("no gateway seen yet");
  } else {
    ImGui::Text("broker %s: %s", state.subscriptions.broker.c_str(),
                state.subscriptions.connected ? "connected" : "DISCONNECTED");
    for (const std::string& f : state.subscriptions.filters) {
      ImGui::PushID(f.c_str());
      const bool remove = ImGui::SmallButton("remove");
      ImGui::SameLine();
      ImGui::TextUnformatted(f.c_str());
      ImGui::PopID();
      if (remove) tab.unsubscribe(state, sink, f, now_ns);  // changes nothing the loop reads
    }
  }
  ImGui::SetNextItemWidth(-90.0f);
  ImGui::InputText("##filter", &tab.filter);
  ImGui::SameLine();
  if (ImGui::Button("subscribe")) tab.subscribe(state, sink, now_ns);
}

void draw_publish(MqttTab& tab, ViewerState& state, CommandSink& sink, int64_t now_ns) {
  section_title("Publish");
  ImGui::InputText("topic", &tab.topic);
  int kind = static_cast<int>(tab.payload_kind);
  ImGui::RadioButton("SLAM v1 (x,y pairs)", &kind, static_cast<int>(PayloadKind::V1Pairs));
  ImGui::SameLine();
  ImGui::RadioButton("raw hex", &kind, static_cast<int>(PayloadKind::Hex));
  ImGui::SameLine();
  ImGui::RadioButton("text", &kind, static_cast<int>(PayloadKind::Text));
  tab.payload_kind = static_cast<PayloadKind>(kind);
  ImGui::InputTextMultiline("##payload", &tab.payload, ImVec2(-1.0f, 48.0f));
  ImGui::SetNextItemWidth(80.0f);
  ImGui::SliderInt("QoS", &tab.qos, 0, 2);
  ImGui::SameLine();
  ImGui::Checkbox("retain", &tab.retain);
  ImGui::SameLine();
  if (ImGui::Button("publish")) tab.publish(state, sink, now_ns);
  error_line(tab.error);
  request_line(state.mqtt_requests);
}

void draw_log(MqttLogView& view, ViewerState& state) {
  const MqttLog& log = state.mqtt;
  section_title("Traffic");
  ImGui::Checkbox("in", &view.show_inbound);
  ImGui::SameLine();
  ImGui::Checkbox("out", &view.show_outbound);
  ImGui::SameLine();
  ImGui::Checkbox("decoded", &view.decoded);
  ImGui::SameLine();
  ImGui::Checkbox("autoscroll", &view.autoscroll);
  ImGui::SameLine();
  if (ImGui::SmallButton("clear")) MqttTab::clear_log(state);
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::InputTextWithHint("##search", "topic contains...", &view.search);
  hint("%zu kept (%zu KiB of %zu), %llu evicted, %llu in / %llu out, %llu dropped", log.size(),
       log.bytes() / 1024, log.max_bytes() / 1024, static_cast<unsigned long long>(log.evicted()),
       static_cast<unsigned long long>(log.inbound()), static_cast<unsigned long long>(log.outbound()),
       static_cast<unsigned long long>(state.mqtt_dropped));
  ImGui::BeginChild("mqtt-log", ImVec2(0, 0), true, ImGuiWindowFlags_HorizontalScrollbar);
  auto row = [&](const MqttEntry& e) {
    ImGui::TextColored(e.inbound ? ImVec4(0.5f, 0.8f, 1, 1) : ImVec4(1, 0.8f, 0.4f, 1), "%s %s [%u]",
                       e.inbound ? "<-" : "->", e.topic.c_str(), e.payload_size);
    ImGui::SameLine();
    const std::string text = view.payload_text(e);
    ImGui::TextUnformatted(text.c_str());
  };
  if (view.filtered()) {
    for (size_t i = 0; i < log.size(); ++i)
      if (view.shows(log.at(i))) row(log.at(i));
  } else {
    // Only the rows on screen are formatted: the log can hold thousands.
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(log.size()));
    while (clipper.Step())
      for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) row(log.at(static_cast<size_t>(i)));
  }
  if (view.autoscroll && ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 20.0f) ImGui::SetScrollHereY(1.0f);
  ImGui::EndChild();
}

}  // namespace

void draw_mqtt_tab(MqttTab& tab, ViewerState& state, CommandSink& sink, int64_t now_ns) {
  draw_subscriptions(tab, state, sink, now_ns);
  draw_publish(tab, state, sink, now_ns);
  draw_log(tab.log, state);
}

}  // namespace slam::viewer
