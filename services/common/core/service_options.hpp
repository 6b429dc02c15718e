#pragma once
// The flags every service has (--domain, --config, --log-level) and one way to parse a command line.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace slam {

struct ServiceOptions {
  int domain = 0;
  std::string log_level = "info";
};

// Adds --domain, --log-level and --config FILE (YAML, see config_file.hpp) to `app`.
void add_service_options(CLI::App& app, ServiceOptions& options);

// Parses the command line. Returns an exit code when the program must stop now: 0 after --help,
// 2 with a one-line error on stderr for bad flags or config. std::nullopt: carry on.
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv);

// Sets up logging for `service` from options; false (with a one-line error) for a bad level.
bool start_logging(const std::string& service, const ServiceOptions& options);

}  // namespace slam
