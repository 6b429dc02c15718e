// slam-viewer: the operator's window. Only wiring: options → DDS edge → window → run → tear down
// in reverse order.
#include <spdlog/spdlog.h>

#include <cstdio>

#include "common/core/shutdown.hpp"
#include "viewer/dds/viewer_node.hpp"
#include "viewer/ui/viewer_app.hpp"

int main(int argc, char** argv) {
  using namespace slam::viewer;
  CLI::App cli{"slam-viewer: map, robots, paths and every control panel (GLFW + Dear ImGui + OpenGL 3.3)"};
  ViewerOptions options;
  add_viewer_options(cli, options);
  if (auto code = slam::parse_command_line(cli, argc, argv)) return *code;
  if (slam::Status s = validate(options); !s) {
    std::fprintf(stderr, "slam-viewer: %s\n", s.message().c_str());
    return 2;
  }
  if (!slam::start_logging("viewer", options.service)) return 2;
  slam::install_shutdown_handlers();

  slam::Counters counters;
  Intake intake;
  auto node = ViewerNode::configure(options.service.domain, intake, counters);
  if (!node) {
    spdlog::error("cannot start the DDS edge: {}", node.message());
    return 1;
  }
  auto app = ViewerApp::create(options, intake, **node, counters);
  if (!app) {
    spdlog::error("cannot open the window: {}", app.message());
    return 1;
  }
  (*node)->set_running();
  const int code = (*app)->run();
  (*node)->set_stopping();
  app->reset();
  node->reset();
  return code;
}
