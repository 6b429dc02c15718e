// CLI11 binding and validation of PlannerOptions.
#include "planner/core/planner_options.hpp"

#include <cmath>
#include <string>

namespace slam::planner {

void add_planner_options(CLI::App& app, PlannerOptions& o) {
  add_service_options(app, o.service);

  TrackerConfig& goals = o.fleet.goals;
  app.add_option("--goals-reach-tolerance-m", goals.reach_tolerance_m,
                 "a waypoint this close (m) counts as reached")
      ->capture_default_str();
  app.add_option("--goals-stray-threshold-m", goals.stray_threshold_m,
                 "a robot further than this (m) off its path segment gets a new plan")
      ->capture_default_str();
  app.add_option("--goals-resend-period-s", goals.resend_period_s,
                 "an unchanged waypoint is sent again this often (s); legacy robots have no ack")
      ->capture_default_str();

  PlannerConfig& planner = o.fleet.planner;
  app.add_option_function<std::string>(
         "--planner-unknown",
         [&planner](const std::string& v) {
           planner.unknown = v == "allowed" ? UnknownPolicy::Allowed : UnknownPolicy::Blocked;
         },
         "unexplored cells on the way to a goal or path request's target: allowed (planned through at "
         "the unknown cost factor, re-planned as the map fills in) or blocked (targets in unexplored "
         "space are refused)")
      ->check(CLI::IsMember({"blocked", "allowed"}))
      ->default_str("allowed");
  app.add_option("--planner-unknown-cost-factor", planner.unknown_cost_factor,
                 "A* step cost multiplier into unexplored cells when allowed (>= 1)")
      ->capture_default_str();
  app.add_option("--planner-ompl-seed", planner.ompl_seed, "OMPL random seed (repeatable sampling)")
      ->capture_default_str();
  app.add_option("--planner-ompl-range-m", planner.ompl_range_m,
                 "longest RRT extension in metres (rrtconnect, rrtstar); 0: OMPL's default")
      ->capture_default_str();
  app.add_option("--planner-ompl-fmt-samples", planner.ompl_fmt_samples,
                 "states FMT* (fmtstar) samples: more take longer and give shorter paths")
      ->capture_default_str();
  app.add_option("--planner-goal-algorithm", planner.goal_algorithm,
                 "what robot goals are planned with: astar, or an OMPL planner (rrtconnect, rrtstar, "
                 "prmstar, fmtstar) with A* answering when it finds nothing in time")
      ->check(CLI::IsMember({"astar", "rrtconnect", "rrtstar", "prmstar", "fmtstar"}))
      ->capture_default_str();
  app.add_option("--planner-goal-time-budget-s", planner.goal_time_budget_s,
                 "time (s) an OMPL goal algorithm gets per plan")
      ->capture_default_str();
  app.add_option("--planner-max-time-budget-s", planner.max_time_budget_s,
                 "path requests asking for more time (s) are refused")
      ->capture_default_str();
  app.add_option("--planner-escape-radius-m", planner.escape_radius_m,
                 "a robot in an inflated or unexplored cell plans from the nearest passable cell this "
                 "close (m)")
      ->capture_default_str();

  ExplorerConfig& explore = o.fleet.explore;
  app.add_option("--explore-min-cluster-cells", explore.min_cluster_cells,
                 "frontier clusters smaller than this are ignored")
      ->capture_default_str();
  app.add_option("--explore-gain-weight", explore.gain_weight,
                 "metres of travel one metre of frontier is worth")
      ->capture_default_str();
  app.add_option("--explore-progress-timeout-s", explore.progress_timeout_s,
                 "a robot not getting closer to its frontier this long gives it up")
      ->capture_default_str();
  app.add_option("--explore-progress-min-m", explore.progress_min_m,
                 "getting this much closer (m) counts as progress")
      ->capture_default_str();
  app.add_option("--explore-blacklist-radius-m", explore.blacklist_radius_m,
                 "frontiers this close (m) to a given-up one are skipped")
      ->capture_default_str();
  app.add_option("--explore-blacklist-rest-s", explore.blacklist_rest_s,
                 "a frontier given up once is offered again after this long (s); twice: for good")
      ->capture_default_str();
  app.add_option_function<std::string>(
         "--explore-unknown",
         [&explore](const std::string& v) {
           explore.unknown = v == "blocked" ? UnknownPolicy::Blocked : UnknownPolicy::Allowed;
         },
         "unexplored cells on an exploring robot's way: allowed (sparse sensors leave gaps) or blocked")
      ->check(CLI::IsMember({"blocked", "allowed"}))
      ->default_str("allowed");
  app.add_option("--explore-completion-grace-s", explore.completion_grace_s,
                 "a robot finding no frontier waits this long (s) before heading home")
      ->capture_default_str();
  app.add_option("--explore-retry-period-s", explore.retry_period_s,
                 "a robot without a reachable frontier looks again this often (s)")
      ->capture_default_str();

  RelocaliseConfig& relocalise = o.fleet.relocalise;
  app.add_option("--explore-return-sigma-m", relocalise.return_sigma_m,
                 "an exploring robot whose pose correction is less certain than this (m) goes back to "
                 "where it was last tied to the map, then explores on; 0: never")
      ->capture_default_str();
  app.add_option("--explore-tied-sigma-m", relocalise.tied_sigma_m,
                 "a tie that makes a robot this certain (m) marks where it is as its place to return to")
      ->capture_default_str();

  CoordinationConfig& coordination = o.coordination;
  app.add_option_function<std::string>(
         "--coordination", [&coordination](const std::string& v) { coordination.enabled = v == "on"; },
         "keep robots from meeting (reservations ahead, waiting, yielding, deadlock breaking): on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->default_str("on");
  app.add_option("--coordination-robot-radius-m", coordination.robot_radius_m,
                 "a robot's radius plus its pose error (m), for coordination")
      ->capture_default_str();
  app.add_option("--coordination-clearance-m", coordination.clearance_m,
                 "free space kept between two robots (m)")
      ->capture_default_str();
  app.add_option("--coordination-lookahead-m", coordination.lookahead_m,
                 "path reserved ahead of each moving robot (m)")
      ->capture_default_str();
  app.add_option("--coordination-yield-search-m", coordination.yield_search_m,
                 "how far (m) a robot in another's way looks for a place to step aside")
      ->capture_default_str();
  app.add_option_function<std::string>(
         "--coordination-sections",
         [&coordination](const std::string& v) { coordination.one_way_sections = v == "on"; },
         "reserve single-lane stretches one way (a robot waits before one used the other way): on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->default_str("off");
  app.add_option_function<std::string>(
         "--coordination-clear-way",
         [&coordination](const std::string& v) { coordination.clear_way = v == "on"; },
         "clear the way of the robot waiting longest into side room (the leader rule): on or off")
      ->check(CLI::IsMember({"on", "off"}))
      ->default_str(coordination.clear_way ? "on" : "off");
  app.add_option("--coordination-clear-after-s", coordination.clear_after_s,
                 "how long (s) a robot waits before its way may be cleared")
      ->capture_default_str();
  app.add_option("--coordination-clear-stall-s", coordination.clear_stall_s,
                 "a leader whose way has not moved for this long (s) gives the lead up")
      ->capture_default_str();

  app.add_option("--loop-rate-hz", o.loop_rate_hz, "goal and waypoint loop rate")->capture_default_str();
  app.add_option("--request-workers", o.request_workers, "threads answering path requests")
      ->capture_default_str();
  app.add_option("--request-queue", o.request_queue, "path requests queued before new ones are refused")
      ->capture_default_str();
  app.add_option("--goal-store", o.goal_store,
                 "file keeping goals and robot homes across restarts (JSON); empty: keep none")
      ->capture_default_str();
  app.add_flag("--no-share{false}", o.share,
               "a lone planner: owns every robot and request from its start (no warm-up, no peers)");
  app.add_option("--peer-timeout-s", o.peer_timeout_s,
                 "a planner unheard this long (s) is gone: its robots and requests move to the others")
      ->capture_default_str();

  AlertConfig& alerts = o.alerts;
  app.add_option("--alerts-battery-low", alerts.battery_low,
                 "a robot reporting a battery below this fraction is alerted and sent home; 0: never")
      ->capture_default_str();
  app.add_option("--alerts-battery-clear-margin", alerts.battery_clear_margin,
                 "the battery alert clears above the low level plus this fraction")
      ->capture_default_str();
  app.add_option("--alerts-service-silent-s", alerts.service_silent_s,
                 "a service whose heartbeats stop this long (s) is alerted as silent")
      ->capture_default_str();
  app.add_option("--alerts-service-forget-s", alerts.service_forget_s,
                 "a silent service is forgotten (its alert clears) after this long (s)")
      ->capture_default_str();
}

Status validate(const PlannerOptions& o) {
  if (auto s = validate(o.fleet); !s) return s;
  if (auto s = validate(o.alerts); !s) return s;
  if (auto s = validate(o.coordination); !s) return s;
  if (!std::isfinite(o.loop_rate_hz) || o.loop_rate_hz < 1.0 || o.loop_rate_hz > 1000.0) {
    return Error{"loop_rate_hz must be between 1 and 1000"};
  }
  if (o.request_workers == 0 || o.request_workers > 16) {
    return Error{"request_workers must be between 1 and 16"};
  }
  if (o.request_queue == 0) return Error{"request_queue must be at least 1"};
  if (auto s = check_seconds("peer_timeout_s", o.peer_timeout_s, 2.0 * kPlannerHeartbeatPeriodS, 60.0); !s)
    return s;
  return Status::ok();
}

}  // namespace slam::planner
