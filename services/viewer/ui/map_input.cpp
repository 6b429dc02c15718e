// Pan, zoom, rotate, flip, fit and click handling over the map (see map_input.hpp).
#include "viewer/ui/map_input.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "viewer/core/auto_fit.hpp"
#include "viewer/core/clicks_tab.hpp"
#include "viewer/core/preview_clicks.hpp"
#include "viewer/gl/gl_api.hpp"

namespace slam::viewer {
namespace {

constexpr double kClickSlopPx = 4.0;  // a press that moves less than this is a click, not a drag
constexpr double kRotateStep = M_PI / 12.0;

bool inside(const Viewport& vp, Vec2 p) {
  return p.x >= vp.x && p.y >= vp.y && p.x < vp.x + vp.width && p.y < vp.y + vp.height;
}

}  // namespace

std::optional<WorldBox> content_box(const ViewerState& state) {
  std::optional<WorldBox> content;
  auto add = [&](const WorldBox& b) { content = content ? unite(*content, b) : b; };
  if (const auto known = state.grid.known_bounds()) add(*known);
  if (WorldBox b; state.robots.bounds(&b)) add(b);
  // A simulated world's walls, when shown: the map then fills in inside a view that already
  // holds the whole world, instead of the view following the exploration.
  if (state.show_world && state.world)
    for (const auto& [a, z] : state.world->walls)
      add({std::min(a.x, z.x), std::min(a.y, z.y), std::max(a.x, z.x), std::max(a.y, z.y)});
  return content;
}

bool fit_box(const ViewerState& state, WorldBox* box) {
  if (auto content = content_box(state)) {
    *box = *content;
    return true;
  }
  if (!state.grid.has_grid()) return false;
  *box = state.grid.bounds();
  return true;
}

void MapInput::handle(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  ImGuiIO& io = ImGui::GetIO();
  const Vec2 mouse{io.MousePos.x, io.MousePos.y};
  const bool over_map = inside(state.view.viewport(), mouse) && !io.WantCaptureMouse;

  // The pose tool owns the left button while armed; Escape or a right click cancels it.
  const bool pose_tool = state.pose_tool.armed();
  if (pose_tool && ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) cancel_pose_tool(state);
  // The path preview owns the left button while armed, alike.
  const bool preview_tool = state.path_preview.armed();
  if (preview_tool && ImGui::IsKeyPressed(GLFW_KEY_ESCAPE)) cancel_path_preview(state);
  if (pose_drag_ && state.pose_tool.dragging()) {
    pose_drag(state, mouse);
    if (!ImGui::IsMouseDown(0)) pose_release(state, sink, mouse, now_ns);
  }
  pose_drag_ = pose_drag_ && state.pose_tool.dragging();
  if (drag_button_ < 0 && over_map) {
    if (pose_tool && ImGui::IsMouseClicked(1)) {
      cancel_pose_tool(state);
    } else if (preview_tool && ImGui::IsMouseClicked(1)) {
      cancel_path_preview(state);
    } else {
      for (int b : {1, 2})
        if (ImGui::IsMouseClicked(b)) {
          drag_button_ = b;
          press_ = last_ = mouse;
          dragged_ = false;
        }
    }
    if (ImGui::IsMouseClicked(0)) {
      if (state.pose_tool.armed()) {
        pose_press(state, mouse);
        pose_drag_ = true;
      } else if (state.path_preview.armed()) {
        path_preview_click(state, sink, mouse, now_ns);
      } else {
        apply_click(state, sink, mouse, MouseButton::Left);
      }
    }
    if (io.MouseWheel != 0.0f) {
      if (io.KeyShift) {
        state.view.rotate_about(mouse, io.MouseWheel * kRotateStep);
      } else {
        state.view.zoom_about(mouse, std::pow(1.2, static_cast<double>(io.MouseWheel)));
      }
      state.view_touched = true;
    }
  }
  if (drag_button_ >= 0) {
    if (std::hypot(mouse.x - press_.x, mouse.y - press_.y) > kClickSlopPx) dragged_ = true;
    if (dragged_ && (mouse.x != last_.x || mouse.y != last_.y)) {
      state.view.pan_pixels(last_, mouse);
      state.view_touched = true;
    }
    last_ = mouse;
    if (!ImGui::IsMouseDown(drag_button_)) {
      if (!dragged_ && drag_button_ == 1) apply_click(state, sink, press_, MouseButton::Right);
      drag_button_ = -1;
    }
  }
  if (!io.WantCaptureKeyboard) {
    const Viewport& vp = state.view.viewport();
    const Vec2 centre{vp.x + vp.width / 2.0, vp.y + vp.height / 2.0};
    if (ImGui::IsKeyPressed(GLFW_KEY_Q)) state.view.rotate_about(centre, kRotateStep);
    if (ImGui::IsKeyPressed(GLFW_KEY_E)) state.view.rotate_about(centre, -kRotateStep);
    if (ImGui::IsKeyPressed(GLFW_KEY_V)) state.view.set_flip_y(!state.view.flip_y());
    WorldBox box;
    if (ImGui::IsKeyPressed(GLFW_KEY_F) && fit_box(state, &box)) state.view.fit(box);
    if (ImGui::IsKeyPressed(GLFW_KEY_Q) || ImGui::IsKeyPressed(GLFW_KEY_E) ||
        ImGui::IsKeyPressed(GLFW_KEY_V) || ImGui::IsKeyPressed(GLFW_KEY_F))
      state.view_touched = true;
  }
}

}  // namespace slam::viewer
