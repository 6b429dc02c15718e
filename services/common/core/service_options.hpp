#pragma once
// The flags every service has (--domain, --config, --log-level), one way to parse a command line,
// one way to report a fatal error, and the transport-free start of every service's main.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "common/core/result.hpp"

namespace slam {

// Exit codes of every program.
inline constexpr int kExitOk = 0;       // done, or --help
inline constexpr int kExitFailure = 1;  // start-up (or, for slamctl, the command) failed
inline constexpr int kExitUsage = 2;    // bad flags, configuration or arguments

struct ServiceOptions {
  int domain = 0;
  std::string log_level = "info";
};

// The one way a program reports why it stops: "PROGRAM: error: MESSAGE", one line on stderr.
void report_error(std::string_view program, std::string_view message);
// report_error(), then the exit code to stop with: `if (!r) return exit_error("slamctl", r.message());`
int exit_error(std::string_view program, std::string_view message, int code = kExitFailure);
// kExitOk for an ok outcome, else exit_error(program, its message).
int exit_code(std::string_view program, const Status& outcome);

// The program a service runs as: "slam-" + service ("gateway" -> "slam-gateway").
std::string program_name(std::string_view service);

// Adds --domain, --log-level and --config FILE (YAML, see config_file.hpp) to `app`.
void add_service_options(CLI::App& app, ServiceOptions& options);

// Validators' range check for a duration option: "KEY must be between MIN and MAX seconds" unless
// `value` is finite and within [min, max].
Status check_seconds(const char* key, double value, double min, double max);

// Parses the command line. Returns an exit code when the program must stop now: 0 after --help,
// 2 with a one-line error on stderr for bad flags or config. std::nullopt: carry on.
std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv);

// Sets up logging for `service` from options; an error (nothing written) for a bad level.
Status start_logging(const std::string& service, const ServiceOptions& options);

// The start of every service's main, before any transport: parses the command line into `options`
// (`add_options(app, options)` adds the service's flags), checks them with `Status validate(Options&)`
// from the options' namespace (found by argument-dependent lookup) and starts logging. Returns the exit code
// when the program must stop now: 0 after --help, 2 after one line "slam-SERVICE: error: ..." on stderr.
// std::nullopt: carry on.
template <class Options, class AddOptions>
std::optional<int> start_service(std::string_view service, const std::string& description, int argc,
                                 char** argv, Options& options, AddOptions add_options) {
  CLI::App app{description};
  add_options(app, options);
  if (auto code = parse_command_line(app, argc, argv)) return code;
  if (Status s = validate(options); !s) {
    report_error(program_name(service), s.message() + " (see --help)");
    return kExitUsage;
  }
  if (Status s = start_logging(std::string(service), options.service); !s) {
    report_error(program_name(service), s.message());
    return kExitUsage;
  }
  return std::nullopt;
}

}  // namespace slam
