#pragma once
// The Map tab's controls without ImGui: export or import the map as ROS map_server YAML + PGM at
// a path on the mapper's disk. An empty or too long path sets `error` and sends nothing; the
// mapper's MapReply lands in ViewerState::replies.
#include <string>

#include "viewer/core/commands.hpp"
#include "viewer/core/viewer_state.hpp"

namespace slam::viewer {

inline constexpr size_t kMaxMapPath = 1024;  // idl: string<1024>

struct MapTab {
  std::string path = "/tmp/slam-map.yaml";
  std::string error;  // the last refused input, shown in red

  void export_map(ViewerState& state, CommandSink& sink) { send(state, sink, false); }
  void import_map(ViewerState& state, CommandSink& sink) { send(state, sink, true); }

 private:
  void send(ViewerState& state, CommandSink& sink, bool import);
};

}  // namespace slam::viewer
