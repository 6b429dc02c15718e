// Main tab: uptime, robots, active alerts, the path preview, message rates with small plots,
// every service's heartbeat.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "common/core/clock.hpp"
#include "viewer/ui/panels.hpp"

namespace slam::viewer {
namespace {

void rate_row(const char* label, const RateMeter& m) {
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "%s %.0f/s (total %llu)", label, static_cast<double>(m.latest()),
                static_cast<unsigned long long>(m.total()));
  float top = 1.0f;
  for (int i = 0; i < m.count(); ++i) top = std::max(top, m.history()[i] * 1.2f);
  ImGui::PushID(label);
  // ImGui 1.86 plots take no negative (right-aligned) width: size from the space left.
  ImGui::PlotLines("##rate", m.history(), m.count(), m.offset(), overlay, 0.0f, top,
                   ImVec2(ImGui::GetContentRegionAvail().x, 36.0f));
  ImGui::PopID();
}

}  // namespace

void draw_main_tab(const ViewerState& state, int64_t now_ns) {
  const double uptime = static_cast<double>(now_ns - state.started_ns) / 1e9;
  ImGui::Text("Uptime %02d:%02d:%02d   frame %.1f ms", static_cast<int>(uptime / 3600),
              static_cast<int>(uptime / 60) % 60, static_cast<int>(uptime) % 60, state.frame_ms);
  ImGui::Text("Robots: %zu online, %zu known   points: %zu", state.robots.online(), state.robots.size(),
              state.robots.total_points());
  if (state.grid.has_grid()) {
    const auto& g = state.grid.info();
    ImGui::Text("Map %ux%u @ %.3f m, layout %u, version %llu%s", g.width, g.height, g.resolution,
                state.grid.layout_id(), static_cast<unsigned long long>(state.grid.version()),
                state.grid.waiting_for_snapshot() ? " (waiting for snapshot)" : "");
  } else {
    ImGui::TextUnformatted("Map: none yet");
  }
  if (!state.grid_error.empty()) ImGui::TextColored({1, 0.4f, 0.4f, 1}, "%s", state.grid_error.c_str());
  ImGui::TextDisabled("GL: %s", state.renderer.c_str());

  const auto alerts = state.alerts.active();
  char alerts_title[48];
  std::snprintf(alerts_title, sizeof alerts_title, "Alerts (%zu)", alerts.size());
  section_title(alerts_title);
  if (alerts.empty()) ImGui::TextDisabled("no active alert");
  const int64_t wall_now = slam::now_ns();  // alerts carry wall-clock stamps
  for (const msg::Alert* a : alerts)
    ImGui::TextColored({1.0f, 0.55f, 0.2f, 1.0f}, "%s", describe(*a, wall_now).c_str());
  ImGui::TextDisabled("path preview: %s", state.path_preview.summary().c_str());

  section_title("Messages");
  rate_row("observations", state.rates.observations);
  rate_row("points", state.rates.points);
  rate_row("map patches", state.rates.patches);
  rate_row("MQTT in", state.rates.mqtt_in);
  rate_row("MQTT out", state.rates.mqtt_out);

  section_title("Services");
  const auto& services = state.services.entries();
  if (services.empty()) ImGui::TextDisabled("no heartbeat yet");
  for (const auto& e : services) {
    const msg::Heartbeat& h = e.heartbeat;
    const bool alive = ServiceHealth::alive(e, now_ns);
    const double ago = static_cast<double>(now_ns - e.last_seen_ns) / 1e9;
    ImGui::PushID(&e);
    // A service that said it was stopping has ended cleanly; silence without that is a failure.
    const bool ended = !alive && h.state == ServiceState::Stopping;
    if (ended) {
      ImGui::TextDisabled("ended");
    } else {
      ImGui::TextColored(alive ? ImVec4(0.3f, 0.9f, 0.3f, 1) : ImVec4(0.9f, 0.3f, 0.3f, 1),
                         alive ? "alive" : "DEAD ");
    }
    ImGui::SameLine();
    // Short enough for the panel; the rest is one click away.
    if (ImGui::TreeNode("svc", "%s  %s  up %.0f s  beat %.1f s ago", h.service.c_str(),
                        msg::service_state_name(h.state), h.uptime_s, ago)) {
      hint("%s on %s, pid %u, %llu beats", h.instance_id.c_str(), h.host.c_str(), h.pid,
           static_cast<unsigned long long>(e.beats));
      for (const auto& [name, value] : h.counters)
        ImGui::Text("%-28s %lld", name.c_str(), static_cast<long long>(value));
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

}  // namespace slam::viewer
