// Map tab actions (see map_tab.hpp).
#include "viewer/core/map_tab.hpp"

namespace slam::viewer {

void MapTab::send(ViewerState& state, CommandSink& sink, bool import) {
  const char* verb = import ? "import" : "export";
  if (path.empty() || path.size() > kMaxMapPath) {
    error = std::string(verb) + ": the YAML path must be 1..1024 characters";
    return;
  }
  state.note_sent(sink.send(MapFileCommand{import, path}), std::string(verb) + " " + path, error);
}

}  // namespace slam::viewer
