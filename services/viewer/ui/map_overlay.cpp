// Robots, paths, targets and ground truth over the map; the view bar (see map_overlay.hpp).
#include "viewer/ui/map_overlay.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "viewer/core/clicks_tab.hpp"
#include "viewer/core/preview_clicks.hpp"
#include "viewer/ui/map_input.hpp"

namespace slam::viewer {
namespace {

ImU32 to_u32(const Rgba& c, float alpha_scale = 1.0f) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, c.a * alpha_scale));
}

ImVec2 screen(const ViewTransform& v, double x, double y) {
  const Vec2 s = v.world_to_screen({x, y});
  return {static_cast<float>(s.x), static_cast<float>(s.y)};
}

// A robot: a triangle pointing along theta (a circle when the heading is unknown).
void draw_robot(ImDrawList* dl, const ViewTransform& v, const Pose& p, bool has_heading, float size_m,
                ImU32 fill, ImU32 outline) {
  const double len = std::max<double>(size_m, 14.0 / v.scale());  // never smaller than 14 px
  if (!has_heading) {
    const ImVec2 c = screen(v, p.x, p.y);
    dl->AddCircleFilled(c, static_cast<float>(len * v.scale() / 2.0), fill, 20);
    dl->AddCircle(c, static_cast<float>(len * v.scale() / 2.0), outline, 20, 1.5f);
    return;
  }
  const double c = std::cos(p.theta), s = std::sin(p.theta);
  auto at = [&](double fwd, double side) {
    return screen(v, p.x + fwd * c - side * s, p.y + fwd * s + side * c);
  };
  const ImVec2 nose = at(len * 0.6, 0.0), left = at(-len * 0.4, len * 0.35),
               right = at(-len * 0.4, -len * 0.35);
  dl->AddTriangleFilled(nose, left, right, fill);
  dl->AddTriangle(nose, left, right, outline, 1.5f);
}

void draw_target(ImDrawList* dl, ImVec2 c, ImU32 col) {
  constexpr float r = 7.0f;
  dl->AddLine({c.x - r, c.y - r}, {c.x + r, c.y + r}, col, 2.5f);
  dl->AddLine({c.x - r, c.y + r}, {c.x + r, c.y - r}, col, 2.5f);
  dl->AddCircle(c, r + 2.0f, col, 16, 1.5f);
}

void draw_path(ImDrawList* dl, const ViewTransform& v, const RobotView& r) {
  const ImU32 col = to_u32(r.settings.color, 0.9f);
  const auto& wps = r.path.waypoints;
  ImVec2 prev = r.has_state ? screen(v, r.state.pose.x, r.state.pose.y) : ImVec2{};
  const size_t from = std::min<size_t>(r.path.current, wps.size());
  bool have_prev = r.has_state;
  for (size_t i = 0; i < wps.size(); ++i) {
    const ImVec2 p = screen(v, wps[i].x, wps[i].y);
    const bool done = i < from;
    if (i >= from) {
      if (have_prev) dl->AddLine(prev, p, col, 2.0f);
      prev = p;
      have_prev = true;
    }
    dl->AddRectFilled({p.x - 3.0f, p.y - 3.0f}, {p.x + 3.0f, p.y + 3.0f},
                      done ? IM_COL32(120, 120, 120, 200) : col);
  }
  if (r.path.status == GoalStatus::Active || r.path.status == GoalStatus::Failed)
    draw_target(dl, screen(v, r.path.target.x, r.path.target.y),
                r.path.status == GoalStatus::Failed ? IM_COL32(255, 40, 40, 255) : col);
}

// A mission's waypoints joined in driving order (closed when looped), numbered, the one being
// driven to ringed. `current` past the end: none is (the draft).
void draw_mission(ImDrawList* dl, const ViewTransform& v, const std::vector<Vec2>& wps, bool loop,
                  size_t current, ImU32 col) {
  for (size_t i = 0; i + 1 < wps.size(); ++i)
    dl->AddLine(screen(v, wps[i].x, wps[i].y), screen(v, wps[i + 1].x, wps[i + 1].y), col, 2.5f);
  if (loop && wps.size() > 2)
    dl->AddLine(screen(v, wps.back().x, wps.back().y), screen(v, wps.front().x, wps.front().y), col, 2.5f);
  for (size_t i = 0; i < wps.size(); ++i) {
    const ImVec2 p = screen(v, wps[i].x, wps[i].y);
    dl->AddCircleFilled(p, 6.0f, col, 12);
    dl->AddCircle(p, 6.0f, IM_COL32(0, 0, 0, 200), 12, 1.0f);
    if (i == current) dl->AddCircle(p, 11.0f, IM_COL32(255, 255, 255, 255), 20, 3.0f);
    const std::string label = std::to_string(i + 1);
    dl->AddText({p.x + 7.0f, p.y + 2.0f}, IM_COL32(255, 255, 255, 230), label.c_str());
  }
}

// The pose tool's drag: a thick arrow from the pressed point (a ring marks it) to the cursor.
void draw_pose_arrow(ImDrawList* dl, const ViewTransform& v, const PoseTool::Arrow& a) {
  constexpr ImU32 kColor = IM_COL32(255, 200, 0, 255);
  const ImVec2 from = screen(v, a.from.x, a.from.y), to = screen(v, a.to.x, a.to.y);
  dl->AddCircle(from, 6.0f, kColor, 16, 2.5f);
  dl->AddLine(from, to, kColor, 3.0f);
  const float dx = to.x - from.x, dy = to.y - from.y, len = std::hypot(dx, dy);
  if (len < 1.0f) return;
  const float ux = dx / len, uy = dy / len, head = std::min(14.0f, len);
  dl->AddTriangleFilled(to, {to.x - head * ux - 0.5f * head * uy, to.y - head * uy + 0.5f * head * ux},
                        {to.x - head * ux + 0.5f * head * uy, to.y - head * uy - 0.5f * head * ux}, kColor);
}

// The previewed path: the polyline with its length at the goal, or a red line from start to goal
// with the reason it failed; while the goal click is awaited, a ring at the start.
void draw_path_preview(ImDrawList* dl, const ViewTransform& v, const PathPreview& preview) {
  constexpr ImU32 kColor = IM_COL32(0, 230, 230, 255);
  constexpr ImU32 kFailed = IM_COL32(255, 60, 60, 255);
  if (const auto start = preview.pending_start())
    dl->AddCircle(screen(v, start->x, start->y), 6.0f, kColor, 16, 2.5f);
  const auto& request = preview.request();
  if (!request) return;
  const ImVec2 from = screen(v, request->start.x, request->start.y),
               to = screen(v, request->goal.x, request->goal.y);
  const auto& result = preview.result();
  const bool ok = result && result->status == msg::PlanStatus::Ok;
  if (ok) {
    for (size_t i = 1; i < result->path.size(); ++i)
      dl->AddLine(screen(v, result->path[i - 1].x, result->path[i - 1].y),
                  screen(v, result->path[i].x, result->path[i].y), kColor, 3.0f);
  } else if (result) {
    dl->AddLine(from, to, kFailed, 1.5f);
  }
  dl->AddCircle(from, 6.0f, ok || !result ? kColor : kFailed, 16, 2.5f);
  draw_target(dl, to, ok || !result ? kColor : kFailed);
  const std::string label = preview.summary();
  dl->AddText({to.x + 13.0f, to.y + 5.0f}, IM_COL32(0, 0, 0, 220), label.c_str());
  dl->AddText({to.x + 12.0f, to.y + 4.0f}, ok || !result ? kColor : kFailed, label.c_str());
}

}  // namespace

void draw_map_overlay(const ViewerState& state) {
  const ViewTransform& v = state.view;
  const Viewport& vp = v.viewport();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  dl->PushClipRect({static_cast<float>(vp.x), static_cast<float>(vp.y)},
                   {static_cast<float>(vp.x + vp.width), static_cast<float>(vp.y + vp.height)}, false);
  if (state.show_world && state.world)
    for (const auto& [a, b] : state.world->walls)
      dl->AddLine(screen(v, a.x, a.y), screen(v, b.x, b.y), IM_COL32(60, 140, 255, 160), 1.5f);
  for (size_t i = 0; i < state.robots.size(); ++i) {
    const RobotView& r = state.robots.at(i);
    if (!r.settings.visible) continue;
    if (state.show_paths && r.settings.show_path && r.has_mission &&
        r.mission.status == MissionStatus::Active)
      draw_mission(dl, v, r.mission.waypoints, r.mission.loop, r.mission.current,
                   to_u32(r.settings.color, 0.6f));
    if (state.show_paths && r.settings.show_path && r.has_path) draw_path(dl, v, r);
  }
  if (state.show_truth && state.truth)
    for (const auto& t : state.truth->robots)
      draw_robot(dl, v, t.true_pose, true, 0.3f, IM_COL32(255, 255, 255, 40), IM_COL32(255, 255, 255, 200));
  if (state.show_robots)
    for (size_t i = 0; i < state.robots.size(); ++i) {
      const RobotView& r = state.robots.at(i);
      if (!r.settings.visible || !r.has_state) continue;
      const bool online = r.state.online;
      draw_robot(dl, v, r.state.pose, r.state.has_heading, r.settings.size_m,
                 to_u32(r.settings.color, online ? 1.0f : 0.4f),
                 online ? IM_COL32(0, 0, 0, 255) : IM_COL32(90, 90, 90, 255));
      if (state.show_names) {
        const ImVec2 c = screen(v, r.state.pose.x, r.state.pose.y);
        // A dark shadow keeps the white name readable over free (light) cells too.
        dl->AddText({c.x + 13.0f, c.y - 17.0f}, IM_COL32(0, 0, 0, 220), r.id.c_str());
        dl->AddText({c.x + 12.0f, c.y - 18.0f}, IM_COL32(255, 255, 255, 240), r.id.c_str());
      }
    }
  if (const auto arrow = state.pose_tool.arrow()) draw_pose_arrow(dl, v, *arrow);
  draw_path_preview(dl, v, state.path_preview);
  // The mission being drawn up, in the tool's own colour.
  const auto& draft = state.mission_tool.waypoints();
  if (!draft.empty())
    draw_mission(dl, v, draft, state.mission_tool.loop(), draft.size(), IM_COL32(255, 200, 0, 220));
  dl->PopClipRect();
}

void draw_view_bar(ViewerState& state) {
  const Viewport& vp = state.view.viewport();
  ImGui::SetNextWindowPos({static_cast<float>(vp.x + 8.0), static_cast<float>(vp.y + 8.0)});
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::Begin("##view", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                   ImGuiWindowFlags_NoNav);
  WorldBox box;
  if (ImGui::Button("Fit") && fit_box(state, &box)) {
    state.view.fit(box);
    state.view_touched = true;
  }
  ImGui::SameLine();
  bool flip = state.view.flip_y();
  if (ImGui::Checkbox("Flip Y", &flip)) {
    state.view.set_flip_y(flip);
    state.view_touched = true;
  }
  const Vec2 centre{vp.x + vp.width / 2.0, vp.y + vp.height / 2.0};
  ImGui::SameLine();
  if (ImGui::Button("Rot +15")) {
    state.view.rotate_about(centre, M_PI / 12.0);
    state.view_touched = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Rot -15")) {
    state.view.rotate_about(centre, -M_PI / 12.0);
    state.view_touched = true;
  }
  ImGui::SameLine();
  if (state.pose_tool.armed()) {
    if (ImGui::Button("Cancel pose")) cancel_pose_tool(state);
  } else if (ImGui::Button("Set pose")) {
    arm_pose_tool(state);
  }
  ImGui::SameLine();
  if (state.path_preview.armed()) {
    if (ImGui::Button("Cancel path")) cancel_path_preview(state);
  } else if (ImGui::Button("Preview path")) {
    arm_path_preview(state);
  }
  ImGui::SameLine();
  const ImVec2 m = ImGui::GetIO().MousePos;
  const Vec2 w = state.view.screen_to_world({m.x, m.y});
  const char* kStates[] = {"unknown", "free", "occupied", "?"};
  if (const auto octet = state.grid.cell_at(w)) {
    const uint8_t cell = *octet;
    ImGui::Text("x %.2f  y %.2f  m  | %s%s%s | %.1f px/m", w.x, w.y, kStates[cell & 3],
                (cell & 4) ? " inflated" : "", (cell & 8) ? " obstructed" : "", state.view.scale());
  } else {
    ImGui::Text("x %.2f  y %.2f  m | %.1f px/m", w.x, w.y, state.view.scale());
  }
  ImGui::End();
}

}  // namespace slam::viewer
