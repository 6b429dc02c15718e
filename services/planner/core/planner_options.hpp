#pragma once
// slam-planner's configuration: the core's FleetConfig plus what only the service edge needs (loop
// rate, path-request workers and queue), with defaults, CLI11/YAML binding and one validator.
// Flags are named after the core's keys: `goals.reach_tolerance_m` is --goals-reach-tolerance-m
// on the command line and `goals: {reach_tolerance_m: 0.15}` in a --config file.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "common/core/result.hpp"
#include "common/core/service_options.hpp"
#include "planner/core/alert_monitor.hpp"
#include "planner/core/fleet.hpp"
#include "planner/core/fleet_coordinator.hpp"

namespace slam::planner {

struct PlannerOptions {
  ServiceOptions service;
  FleetConfig fleet;
  CoordinationConfig coordination;  // robots kept from meeting (--coordination off: ignored)
  double loop_rate_hz = 20.0;       // goal ticks, waypoint streaming and path publishing
  uint32_t request_workers = 1;     // threads answering PathRequests, each with its own planner
  uint32_t request_queue = 64;      // queued PathRequests beyond this are answered TIMEOUT at once
  std::string goal_store = "run/data/goals.json";  // goals and homes kept across restarts; "" = none
  // Several planners share the robots: each robot's goal tracking and waypoints, and each path
  // request, belong to one of the planners heard within peer_timeout_s (common/core/ownership.hpp).
  // share false (--no-share): a lone planner that owns everything from its start, no warm-up.
  bool share = true;
  double peer_timeout_s = 1.5;
  AlertConfig alerts;  // robot offline, battery low (sent home), service silent
};

// Planner heartbeats go out this often: peer_timeout_s must span a few of them.
inline constexpr double kPlannerHeartbeatPeriodS = 0.5;

// Adds the common flags and every planner flag to `app`, bound to `options`.
void add_planner_options(CLI::App& app, PlannerOptions& options);

// Ok, or the first bad key with the reason.
Status validate(const PlannerOptions& options);

}  // namespace slam::planner
