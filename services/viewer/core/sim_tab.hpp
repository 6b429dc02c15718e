#pragma once
// The Sim tab's controls and what they send, without ImGui: spawn, remove, pause, resume, set
// world, set noise, set speed. Values out of the simulator's ranges set `error` and send nothing;
// every command sent is tracked in ViewerState::sim_requests until the simulator's reply.
#include <cstdint>
#include <string>

#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

inline constexpr int kMaxSpawn = 1000;
inline constexpr size_t kMaxSimRobotId = 64;  // idl: string<64>
inline constexpr size_t kMaxSimWorld = 1024;  // idl: string<1024>

struct SimTab {
  int count = 1;
  std::string robot_id;
  std::string world = "office";
  double range_noise_sd = 0.01;  // metres, 0..10
  double dropout = 0.0;          // 0..1
  double odometry_drift = 0.0;   // metres per metre, 0..10
  double speed_factor = 1.0;     // (0, 1000]
  std::string error;             // the last refused input, shown in red

  void spawn(ViewerState& state, CommandSink& sink, int64_t now_ns);
  void remove(ViewerState& state, CommandSink& sink, int64_t now_ns);
  void pause(ViewerState& state, CommandSink& sink, int64_t now_ns);
  void resume(ViewerState& state, CommandSink& sink, int64_t now_ns);
  void set_world(ViewerState& state, CommandSink& sink, int64_t now_ns);
  void set_noise(ViewerState& state, CommandSink& sink, int64_t now_ns);
  void set_speed(ViewerState& state, CommandSink& sink, int64_t now_ns);

 private:
  void send(ViewerState& state, CommandSink& sink, SimCommandKind kind, const std::string& what,
            int64_t now_ns);
};

}  // namespace slam::viewer
