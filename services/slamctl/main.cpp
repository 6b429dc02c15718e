// slamctl: script the fleet without the GUI. Each subcommand talks DDS, prints what it got and exits
// non-zero with a one-line reason on failure or timeout. Only wiring: the subcommand table
// (commands.hpp) -> parse -> participant -> the parsed subcommand's handler.
#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "slamctl/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"slamctl: inspect and command the SLAM fleet over DDS"};
  slam::ServiceOptions options;
  options.log_level = "warn";
  slam::add_service_options(app, options);
  double timeout_s = 5.0;
  app.add_option("--timeout", timeout_s, "seconds to wait for services and replies")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  const slam::ctl::Handlers handlers = slam::ctl::add_subcommands(app);

  if (auto code = slam::parse_command_line(app, argc, argv)) return *code;
  if (slam::Status s = slam::start_logging("slamctl", options); !s)
    return slam::exit_error("slamctl", s.message(), slam::kExitUsage);
  slam::install_shutdown_handlers();

  auto participant = slam::dds::Participant::create(options.domain, "slamctl");
  if (!participant) return slam::exit_error("slamctl", participant.message());
  slam::ctl::Session session(std::move(*participant),
                             std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000)));
  return slam::ctl::run_parsed(handlers, session);
}
