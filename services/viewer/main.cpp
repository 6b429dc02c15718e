// slam-viewer: the operator's window. Only wiring: options → DDS edge → window → run → tear down
// in reverse order (the window, then the DDS edge, as they go out of scope).
#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "viewer/dds/viewer_node.hpp"
#include "viewer/ui/viewer_app.hpp"

int main(int argc, char** argv) {
  using namespace slam::viewer;
  ViewerOptions options;
  if (auto code = slam::start_service(
          "viewer",
          "slam-viewer: map, robots, paths and every control panel (GLFW + Dear ImGui + OpenGL 3.3)", argc,
          argv, options, add_viewer_options))
    return *code;
  slam::install_shutdown_handlers();

  slam::Counters counters;
  Intake intake;
  auto node = ViewerNode::configure(options.service.domain, intake, counters);
  if (!node) return slam::exit_error("slam-viewer", "cannot start the DDS edge: " + node.message());
  auto app = ViewerApp::create(options, intake, **node, counters);
  if (!app) return slam::exit_error("slam-viewer", "cannot open the window: " + app.message());
  (*node)->set_running();
  const int code = (*app)->run();
  (*node)->set_stopping();
  return code;
}
