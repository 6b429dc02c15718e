// slam-mapper: placeholder process until its issue lands; it takes the common flags and exits.
#include "common/service_options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"slam-mapper"};
  slam::ServiceOptions options;
  slam::add_service_options(app, options);
  if (auto code = slam::parse_command_line(app, argc, argv)) return *code;
  return slam::start_logging("mapper", options) ? 0 : 2;
}
