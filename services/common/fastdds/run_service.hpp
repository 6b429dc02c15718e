#pragma once
// The Fast DDS part of every server service's main: the node (which owns the participant), signal
// handling, the heartbeat and the loop, with the same exit codes and error lines everywhere.
#include <spdlog/spdlog.h>

#include <functional>
#include <string>
#include <string_view>

#include "common/core/counters.hpp"
#include "common/core/service_options.hpp"
#include "common/core/shutdown.hpp"
#include "common/fastdds/heartbeat.hpp"

namespace slam {

// Runs `Node` until SIGINT/SIGTERM after start_service() (core/service_options.hpp) succeeded:
// Node::create(options, counters) -> heartbeat on the node's participant, RUNNING -> run_once() until
// shutdown -> STOPPING -> heartbeat and node torn down in reverse order. Returns 0, or 1 after one
// line "slam-SERVICE: error: ..." when the node or its heartbeat cannot start.
// Node needs: static Result<std::unique_ptr<Node>> create(const Options&, Counters&);
//             dds::Participant& participant(); void run_once();
// `created` runs once the node exists, just before its heartbeat starts (the mapper hands over
// the heartbeat of its domain claim there). Node may set its heartbeat period with `static constexpr
// std::chrono::milliseconds kHeartbeatPeriod` (1 s otherwise).
template <class Node>
constexpr std::chrono::milliseconds heartbeat_period() {
  if constexpr (requires { Node::kHeartbeatPeriod; }) {
    return Node::kHeartbeatPeriod;
  } else {
    return std::chrono::seconds(1);
  }
}

template <class Node, class Options>
int run_service(std::string_view service, const Options& options, const std::function<void()>& created = {}) {
  install_shutdown_handlers();
  Counters counters;
  auto node = Node::create(options, counters);
  if (!node) {
    report_error(program_name(service), node.message());
    return kExitFailure;
  }
  if (created) created();
  auto heartbeat = HeartbeatPublisher::start((*node)->participant(), std::string(service), counters,
                                             heartbeat_period<Node>());
  if (!heartbeat) {
    report_error(program_name(service), "heartbeat: " + heartbeat.message());
    return kExitFailure;
  }
  (*heartbeat)->set_state(SERVICE_RUNNING);

  while (!shutdown_requested()) (*node)->run_once();

  spdlog::info("{} stopping", service);
  (*heartbeat)->set_state(SERVICE_STOPPING);
  heartbeat->reset();
  node->reset();
  return kExitOk;
}

}  // namespace slam
