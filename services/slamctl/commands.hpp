#pragma once
// slamctl's subcommands: a table of {name, help, add_options}, each entry defined next to its handler
// in commands.cpp. A handler talks DDS through a Session and returns the process exit code (0 done,
// 1 failed or timed out, 2 bad arguments), with one line "slamctl: error: ..." on stderr on failure.
#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "common/core/request_retry.hpp"
#include "common/fastdds/fast_topics.hpp"

namespace slam::ctl {

class Session {
 public:
  Session(std::unique_ptr<dds::Participant> participant, std::chrono::milliseconds timeout)
      : participant_(std::move(participant)), timeout_(timeout) {}
  dds::Participant& participant() { return *participant_; }
  std::chrono::milliseconds timeout() const { return timeout_; }
  int domain() const { return participant_->domain_id(); }
  // A goal id no other client uses (request ids are stamped by the Requester).
  uint64_t next_goal_id();

 private:
  std::unique_ptr<dds::Participant> participant_;
  std::chrono::milliseconds timeout_;
  RequestIdSource goal_ids_;
};

// Runs a parsed subcommand; returns the exit code.
using Handler = std::function<int(Session&)>;

struct Subcommand {
  std::string_view name;
  std::string_view help;
  // Adds the subcommand's arguments (and its own subcommands) to `cli`, the CLI11 subcommand made
  // from name and help; returns the handler that runs it with the values parsed into them.
  Handler (*add_options)(CLI::App& cli);
};

// Every subcommand, in the order --help lists them.
const std::vector<Subcommand>& subcommands();

// Every subcommand of the table added to `app` (exactly one required), each with its handler.
using Handlers = std::vector<std::pair<const CLI::App*, Handler>>;
Handlers add_subcommands(CLI::App& app);
// Runs the handler of the subcommand parsed; kExitUsage when none was.
int run_parsed(const Handlers& handlers, Session& session);

}  // namespace slam::ctl
