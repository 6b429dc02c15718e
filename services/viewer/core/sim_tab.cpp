// Sim tab actions (see sim_tab.hpp).
#include "viewer/core/sim_tab.hpp"

#include <cstdio>

namespace slam::viewer {
namespace {

// lo <= v <= hi, or lo < v <= hi when `open_low`; NaN is never in range.
bool in_range(double v, double lo, double hi, bool open_low = false) {
  return (open_low ? v > lo : v >= lo) && v <= hi;
}

std::string num(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%g", v);
  return s;
}

}  // namespace

void SimTab::send(ViewerState& state, CommandSink& sink, SimCommandKind kind, const std::string& what,
                  int64_t now_ns) {
  SimCommand c;
  c.kind = kind;
  c.count = static_cast<uint32_t>(count < 1 ? 1 : count);
  c.robot_id = robot_id;
  c.world = world;
  c.range_noise_sd = range_noise_sd;
  c.dropout = dropout;
  c.odometry_drift = odometry_drift;
  c.speed_factor = speed_factor;
  if (const uint64_t id = state.note_sent(sink.send(c), what, error))
    state.sim_requests.sent(id, what, now_ns);
}

void SimTab::spawn(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  if (count < 1 || count > kMaxSpawn) {
    error = "spawn: count must be 1.." + std::to_string(kMaxSpawn);
    return;
  }
  send(state, sink, SimCommandKind::Spawn,
       "spawn " + std::to_string(count) + (count == 1 ? " robot" : " robots"), now_ns);
}

void SimTab::remove(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  if (robot_id.empty() || robot_id.size() > kMaxSimRobotId) {
    error = "remove: the robot id must be 1..64 characters";
    return;
  }
  send(state, sink, SimCommandKind::Remove, "remove " + robot_id, now_ns);
}

void SimTab::pause(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  send(state, sink, SimCommandKind::Pause, "pause", now_ns);
}

void SimTab::resume(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  send(state, sink, SimCommandKind::Resume, "resume", now_ns);
}

void SimTab::set_world(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  if (world.empty() || world.size() > kMaxSimWorld) {
    error = "set world: give a built-in world name or a file path (1..1024 characters)";
    return;
  }
  send(state, sink, SimCommandKind::SetWorld, "set world " + world, now_ns);
}

void SimTab::set_noise(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  if (!in_range(range_noise_sd, 0.0, 10.0) || !in_range(dropout, 0.0, 1.0) ||
      !in_range(odometry_drift, 0.0, 10.0)) {
    error = "set noise: range noise sd and odometry drift must be 0..10, dropout 0..1";
    return;
  }
  send(state, sink, SimCommandKind::SetNoise,
       "set noise (sd " + num(range_noise_sd) + " m, dropout " + num(dropout) + ", drift " +
           num(odometry_drift) + ")",
       now_ns);
}

void SimTab::set_speed(ViewerState& state, CommandSink& sink, int64_t now_ns) {
  if (!in_range(speed_factor, 0.0, 1000.0, true)) {
    error = "set speed: the speed factor must be in (0, 1000]";
    return;
  }
  send(state, sink, SimCommandKind::SetSpeed, "set speed x" + num(speed_factor), now_ns);
}

}  // namespace slam::viewer
