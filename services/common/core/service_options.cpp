#include "common/core/service_options.hpp"

#include <cmath>
#include <filesystem>
#include <iostream>

#include "common/core/config_file.hpp"
#include "common/core/log.hpp"

namespace slam {

void report_error(std::string_view program, std::string_view message) {
  std::cerr << program << ": error: " << message << "\n";
}

int exit_error(std::string_view program, std::string_view message, int code) {
  report_error(program, message);
  return code;
}

int exit_code(std::string_view program, const Status& outcome) {
  return outcome ? kExitOk : exit_error(program, outcome.message());
}

std::string program_name(std::string_view service) {
  return "slam-" + std::string(service);
}

Status check_seconds(const char* key, double value, double min, double max) {
  if (!std::isfinite(value) || value < min || value > max) {
    return Error{std::string(key) + " must be between " + std::to_string(min) + " and " +
                 std::to_string(max) + " seconds"};
  }
  return Status::ok();
}

void add_service_options(CLI::App& app, ServiceOptions& options) {
  app.add_option("--domain", options.domain, "DDS domain id")
      ->check(CLI::Range(0, 232))
      ->capture_default_str();
  app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error or off")
      ->capture_default_str();
  app.config_formatter(std::make_shared<YamlConfig>());
  app.set_config("--config", "", "YAML file of option: value pairs (command-line flags win)");
  app.allow_config_extras(CLI::config_extras_mode::error);  // a misspelt key is an error, not ignored
}

std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  // Name the program by its file name, not the path it was started by, in usage and errors.
  if (app.get_name().empty() && argc > 0) app.name(std::filesystem::path(argv[0]).filename().string());
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return kExitOk;
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return kExitOk;
  } catch (const CLI::ParseError& e) {
    report_error(app.get_name(), std::string(e.what()) + " (see --help)");
    return kExitUsage;
  }
  return std::nullopt;
}

Status start_logging(const std::string& service, const ServiceOptions& options) {
  if (setup_logging(service, options.log_level)) return Status::ok();
  return Error{"--log-level " + options.log_level + " is not one of trace, debug, info, warn, error, off"};
}

}  // namespace slam
