// Feeding the render thread's state from a drained intake batch (see viewer_state.hpp).
#include "viewer/core/viewer_state.hpp"

#include <spdlog/spdlog.h>

#include <utility>

namespace slam::viewer {

void MessageRates::tick(int64_t now_ns) {
  observations.tick(now_ns);
  points.tick(now_ns);
  patches.tick(now_ns);
  mqtt_in.tick(now_ns);
  mqtt_out.tick(now_ns);
}

void ViewerState::ingest(IntakeBatch& batch, int64_t now_ns) {
  if (batch.snapshot) {
    if (Status s = grid.apply_snapshot(std::move(*batch.snapshot)); !s) {
      grid_error = s.message();
      spdlog::warn("ignoring grid snapshot: {}", s.message());
    } else {
      grid_error.clear();
      ++snapshots;
    }
  }
  for (const auto& p : batch.patches) {
    const PatchResult r = grid.apply_patch(p);
    if (r == PatchResult::Applied) {
      rates.patches.add();
    } else if (r != PatchResult::Stale) {
      ++patches_dropped;
    }
  }
  // Corrections first: this frame's points are placed through the newest one.
  for (auto& c : batch.corrections) robots.ingest(std::move(c));
  for (const auto& o : batch.observations) {
    robots.ingest(o);
    rates.observations.add();
    rates.points.add(o.hits_xy.size() / 2);
  }
  for (auto& s : batch.states) robots.ingest(std::move(s));
  for (const auto& p : batch.poses) robots.ingest(p);
  for (auto& p : batch.paths) robots.ingest(std::move(p));
  for (auto& m : batch.missions) robots.ingest(std::move(m));
  for (const auto& f : batch.forgets) {
    robots.forget(f.robot_id);
    if (selected_robot == f.robot_id) selected_robot = "*";
  }
  for (auto& a : batch.alerts) alerts.update(std::move(a));
  for (auto& r : batch.path_replies) path_preview.reply(std::move(r));
  for (auto& h : batch.heartbeats) services.update(std::move(h), now_ns);
  for (auto& e : batch.mqtt) {
    (e.inbound ? rates.mqtt_in : rates.mqtt_out).add();
    mqtt.push(std::move(e));
  }
  mqtt_dropped += batch.mqtt_dropped;
  if (batch.subscriptions) {
    subscriptions = std::move(*batch.subscriptions);
    have_subscriptions = true;
  }
  if (batch.world) world = std::move(batch.world);
  if (batch.truth) truth = std::move(batch.truth);
  for (auto& r : batch.replies) {
    pose_requests.reply(r.request_id, r.result == 0, r.message);
    status_line =
        "request " + std::to_string(r.request_id) + (r.result == 0 ? ": ok " : ": failed ") + r.message;
    replies.push_front(std::move(r));
    if (replies.size() > 16) replies.pop_back();
  }
  for (auto& r : batch.mqtt_replies) mqtt_requests.reply(r.request_id, r.ok, std::move(r.message));
  for (auto& r : batch.sim_replies) sim_requests.reply(r.request_id, r.ok, std::move(r.message));
  mqtt_requests.tick(now_ns);
  sim_requests.tick(now_ns);
  pose_requests.tick(now_ns);
  path_preview.tick(now_ns);
  rates.tick(now_ns);
}

uint64_t ViewerState::note_sent(uint64_t id, const std::string& what, std::string& error) {
  if (id == 0) {
    error = "NOT sent (the DDS writer refused it): " + what;
  } else {
    error.clear();
    status_line = what + " (request " + std::to_string(id) + ")";
  }
  return id;
}

GoalMode ViewerState::mode_for(const std::string& robot_id) {
  if (robot_id != "*")
    if (RobotView* r = robots.find(robot_id)) return r->settings.mode;
  return robots.defaults().mode;
}

}  // namespace slam::viewer
