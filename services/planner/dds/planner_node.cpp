// PlannerNode: configure, and the loop pass that turns intake into core calls and samples.
#include "planner/dds/planner_node.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <utility>

#include "common/core/clock.hpp"
#include "common/core/service_identity.hpp"

namespace slam::planner {

namespace {

std::string counter_name(PlanStatus status) {
  return std::string("replies_") + msg::plan_status_id(status);
}

int64_t to_ns(double seconds) {
  return static_cast<int64_t>(seconds * 1e9);
}

// Without sharing, no warm-up: a lone planner drives robots and answers requests from its start.
OwnershipConfig ownership_config(const PlannerOptions& o) {
  const int64_t timeout = to_ns(o.peer_timeout_s);
  // Longer than a heartbeat period past the timeout: by then every live peer has heard this
  // planner's heartbeats (discovery included) and dropped the robots it takes.
  return {timeout, o.share ? timeout + to_ns(2.0 * kPlannerHeartbeatPeriodS) : 0};
}

}  // namespace

PlannerNode::Metrics::Metrics(Counters& c)
    : path_requests(c.get("path_requests")),
      path_requests_repeated(c.get("path_requests_repeated")),
      replies{},
      goals_accepted(c.get("goals_accepted")),
      goals_rejected(c.get("goals_rejected")),
      goals_reached(c.get("goals_reached")),
      goals_failed(c.get("goals_failed")),
      goals_replayed(c.get("goals_replayed")),
      store_failures(c.get("store_failures")),
      replans(c.get("replans")),
      waypoints_sent(c.get("waypoints_sent")),
      paths_published(c.get("paths_published")),
      robot_positions(c.get("robot_positions")),
      robot_positions_rejected(c.get("robot_positions_rejected")),
      snapshots(c.get("snapshots")),
      snapshots_rejected(c.get("snapshots_rejected")),
      patches_applied(c.get("patches_applied")),
      patches_skipped(c.get("patches_skipped")),
      map_version(c.get("map_version")),
      write_failures(c.get("write_failures")),
      path_requests_not_owned(c.get("path_requests_not_owned")),
      robots_owned(c.get("robots_owned")),
      planners_live(c.get("planners_live")),
      robots_held(c.get("robots_held")),
      deadlocks_broken(c.get("deadlocks_broken")),
      replans_around_robots(c.get("replans_around_robots")),
      longest_wait_ms(c.get("longest_wait_ms")),
      revisits(c.get("revisits")) {
  for (size_t i = 0; i < replies.size(); ++i) replies[i] = &c.get(counter_name(static_cast<PlanStatus>(i)));
}

PlannerNode::PlannerNode(const PlannerOptions& options, Counters& counters)
    : options_(options),
      period_(std::max<int64_t>(1, static_cast<int64_t>(std::lround(1000.0 / options.loop_rate_hz)))),
      metrics_(counters),
      counters_(counters),
      robots_forgotten_(counters.get("robots_forgotten")),
      fleet_(options.fleet),
      coordinator_(options.coordination),
      // The instance id this process's heartbeats carry (host:pid), so peers and self agree.
      ownership_(ServiceIdentity::of("planner").instance_id, monotonic_ns(), ownership_config(options)),
      missions_(counters) {}

Result<std::unique_ptr<PlannerNode>> PlannerNode::create(const PlannerOptions& options, Counters& counters) {
  std::unique_ptr<PlannerNode> node(new PlannerNode(options, counters));
  SLAM_TRY(node->configure());
  return node;
}

Status PlannerNode::configure() {
  auto store = GoalStore::open(options_.goal_store);
  if (!store) return store.error();
  goal_store_ = std::move(*store);
  resume_goals();

  auto participant = dds::Participant::create(options_.service.domain, "slam-planner");
  if (!participant) return participant.error();
  participant_ = std::move(*participant);

  auto replies = dds::make_writer(*participant_, dds::kPathReply);
  if (!replies) return replies.error();
  reply_writer_ = std::move(*replies);
  auto waypoints = dds::make_writer(*participant_, dds::kWaypointCommand);
  if (!waypoints) return waypoints.error();
  waypoint_writer_ = std::move(*waypoints);
  auto paths = dds::make_writer(*participant_, dds::kRobotPath);
  if (!paths) return paths.error();
  path_writer_ = std::move(*paths);

  try {
    workers_ = std::make_unique<RequestWorkers>(
        options_.fleet.planner, options_.request_workers, options_.request_queue,
        [this](const PathJob& job, const PlanResult& result) { reply(job, result); });
  } catch (const std::exception& e) {
    return Error{std::string("cannot start the path request workers: ") + e.what()};
  }

  auto alerts = AlertNode::create(*participant_, options_.alerts, ownership_.self(), counters_);
  if (!alerts) return alerts.error();
  alerts_ = std::move(*alerts);

  // Readers last: from here on callbacks run, and everything they touch exists. Heartbeats first:
  // the request intake asks the ownership.
  if (options_.share) {
    auto heartbeats = dds::make_reader(*participant_, dds::kHeartbeat,
                                       [this](const slam::Heartbeat& h, const auto&) { on_heartbeat(h); });
    if (!heartbeats) return heartbeats.error();
    heartbeat_reader_ = std::move(*heartbeats);
    auto reports = dds::make_reader(*participant_, dds::kRobotPath,
                                    [this](const slam::RobotPath& p, const auto&) { on_path(p); });
    if (!reports) return reports.error();
    path_reader_ = std::move(*reports);
  }
  auto snapshots =
      dds::make_reader(*participant_, dds::kGridSnapshot,
                       [this](const slam::GridSnapshot& s, const auto&) { intake_.push_snapshot(s); });
  if (!snapshots) return snapshots.error();
  snapshot_reader_ = std::move(*snapshots);
  auto patches = dds::make_reader(*participant_, dds::kGridTiles,
                                  [this](const slam::GridTiles& p, const auto&) { intake_.push_patch(p); });
  if (!patches) return patches.error();
  patch_reader_ = std::move(*patches);
  auto states =
      dds::make_reader(*participant_, dds::kRobotState, [this](const slam::RobotState& s, const auto&) {
        intake_.push_state(s);
        alerts_->on_state(s);
      });
  if (!states) return states.error();
  state_reader_ = std::move(*states);
  // The pose stream: every gateway's robots ten times a second (a state record comes once a second).
  auto digests =
      dds::make_reader(*participant_, dds::kFleetDigest,
                       [this](const slam::FleetDigest& d, const auto&) { intake_.push_digest(d); });
  if (!digests) return digests.error();
  digest_reader_ = std::move(*digests);
  auto corrections = dds::make_reader(*participant_, dds::kPoseCorrection,
                                      [this](const slam::PoseCorrection& c, const auto&) {
                                        intake_.push_correction(c);
                                        alerts_->on_correction(c);
                                      });
  if (!corrections) return corrections.error();
  correction_reader_ = std::move(*corrections);
  auto goals = dds::make_reader(*participant_, dds::kNavGoal,
                                [this](const slam::NavGoal& g, const dds::fdds::SampleInfo& info) {
                                  intake_.push_goal(g, info.source_timestamp.to_ns());
                                });
  if (!goals) return goals.error();
  goal_reader_ = std::move(*goals);
  SLAM_TRY(missions_.connect(*participant_));
  auto requests =
      dds::make_reader(*participant_, dds::kPathRequest,
                       [this](const slam::PathRequest& r, const auto&) { intake_.push_request(r); });
  if (!requests) return requests.error();
  request_reader_ = std::move(*requests);
  auto forgets =
      dds::make_reader(*participant_, dds::kForgetRobot, [this](const slam::ForgetRobot& f, const auto&) {
        std::lock_guard lock(forget_mutex_);
        forget_.push_back(f.robot_id().to_string());
      });
  if (!forgets) return forgets.error();
  forget_reader_ = std::move(*forgets);
  spdlog::info("planner ready on domain {} ({} request worker(s), loop {} Hz)", options_.service.domain,
               options_.request_workers, options_.loop_rate_hz);
  if (options_.share) {
    spdlog::info("planner '{}' shares the robots and requests; it drives robots after a {:.1f} s warm-up",
                 ownership_.self(), static_cast<double>(ownership_config(options_).warmup_ns) * 1e-9);
  }
  return Status::ok();
}

void PlannerNode::run_once() {
  intake_.wait(period_);
  intake_.drain(batch_);
  apply_grid(batch_);
  apply_positions(batch_.positions);
  apply_uncertainties(batch_.uncertainties);
  apply_goals(batch_.goals);
  const int64_t now = monotonic_ns();
  update_ownership(now);
  apply_reports();
  apply_forgets();
  alerts_->tick(now, [&](const std::string& key) {
    std::lock_guard lock(ownership_mutex_);
    return ownership_.owns(key, now);
  });
  missions_.run(fleet_, goal_store_);
  submit_requests(batch_.requests);
  count_replans();
  fleet_.tick(grid_, now);
  report_revisits();
  coordinate(now);
  publish_paths();
  stream_waypoints(now);
  flush_store();
}

void PlannerNode::count_replans() {
  // A robot that still has waypoints but wants a plan strayed or lost its path to the map.
  if (grid_.empty()) return;
  for (const std::string& id : robots_) {
    const GoalTracker* t = fleet_.tracker(id);
    if (t != nullptr && fleet_.owns(id) && t->needs_plan() && !t->waypoints().empty()) {
      bump(metrics_.replans);
      spdlog::info("robot '{}': re-planning goal {} (path blocked or robot off its path)", id,
                   t->goal().goal_id);
    }
  }
}

void PlannerNode::publish_paths() {
  for (const std::string& id : fleet_.take_changed()) {
    const GoalTracker* t = fleet_.tracker(id);
    if (t == nullptr) continue;
    fill_path(id, *t, path_);
    bump(path_writer_->write(path_) ? metrics_.paths_published : metrics_.write_failures);
    auto [it, inserted] = reported_status_.try_emplace(id, t->status());
    if (!inserted && it->second == t->status()) continue;
    it->second = t->status();
    if (t->status() == GoalStatus::Reached || t->status() == GoalStatus::Failed)
      goal_store_.finish(id, t->goal().goal_id);
    if (t->status() == GoalStatus::Reached) {
      bump(metrics_.goals_reached);
      spdlog::info("robot '{}' reached goal {}", id, t->goal().goal_id);
    } else if (t->status() == GoalStatus::Failed) {
      bump(metrics_.goals_failed);
      warn("failed:" + id,
           "robot '" + id + "' failed goal " + std::to_string(t->goal().goal_id) + ": " + t->reason());
    }
  }
}

void PlannerNode::coordinate(int64_t now_ns) {
  if (!coordinator_.enabled()) return;
  coordinator_.coordinate(fleet_, grid_, now_ns);
  metrics_.robots_held.store(static_cast<int64_t>(coordinator_.held()), std::memory_order_relaxed);
  metrics_.deadlocks_broken.store(static_cast<int64_t>(coordinator_.deadlocks()), std::memory_order_relaxed);
  metrics_.replans_around_robots.store(static_cast<int64_t>(coordinator_.replans()),
                                       std::memory_order_relaxed);
  metrics_.longest_wait_ms.store(std::llround(coordinator_.longest_wait_seen_s() * 1000.0),
                                 std::memory_order_relaxed);
}

void PlannerNode::stream_waypoints(int64_t now_ns) {
  fleet_.due_waypoints(now_ns, due_);
  if (coordinator_.enabled()) coordinator_.dispatch(fleet_, due_);
  for (const DueWaypoint& d : due_) {
    command_.robot_id(d.robot_id);
    // Ids follow the wall clock (ms) and grow per robot, so a planner taking a robot over continues
    // above its previous owner's ids while the planners' clocks agree within the takeover time.
    uint64_t& seq = waypoint_seq_[d.robot_id];
    seq = std::max(seq + 1, static_cast<uint64_t>(slam::now_ns() / 1'000'000));
    command_.seq(seq);
    command_.waypoint(msg::to_idl(d.waypoint));
    to_points(d.remaining, command_.remaining());
    bump(waypoint_writer_->write(command_) ? metrics_.waypoints_sent : metrics_.write_failures);
  }
}

void PlannerNode::on_heartbeat(const slam::Heartbeat& heartbeat) {
  if (heartbeat.service().to_string() != "planner") return;
  const std::string instance = heartbeat.instance_id().to_string();
  std::lock_guard lock(ownership_mutex_);
  ownership_.observe(instance, heartbeat.state() == SERVICE_STOPPING, monotonic_ns());
}

void PlannerNode::on_path(const slam::RobotPath& sample) {
  PathReport report = to_report(msg::from_idl(sample));
  std::lock_guard lock(reports_mutex_);
  reports_[sample.robot_id().to_string()] = std::move(report);
}

void PlannerNode::update_ownership(int64_t now_mono_ns) {
  std::vector<std::string> live;
  size_t owned = 0;
  gone_.clear();
  {
    std::lock_guard lock(ownership_mutex_);
    ownership_.expire(now_mono_ns, &gone_);
    if (ownership_.version() != ownership_version_) {
      ownership_version_ = ownership_.version();
      live = ownership_.live();
    }
    owned = fleet_.update_ownership([&](const std::string& id) { return ownership_.owns(id, now_mono_ns); });
  }
  metrics_.robots_owned.store(static_cast<int64_t>(owned), std::memory_order_relaxed);
  for (const std::string& id : gone_) {
    spdlog::warn("planner '{}' silent for {} s: its robots move to the others", id, options_.peer_timeout_s);
  }
  if (live.empty()) return;
  metrics_.planners_live.store(static_cast<int64_t>(live.size()), std::memory_order_relaxed);
  std::string ids;
  for (const std::string& id : live) ids += (ids.empty() ? "" : ", ") + id;
  if (options_.share) spdlog::info("planners sharing the robots: {} ({})", live.size(), ids);
}

void PlannerNode::apply_reports() {
  reports_taken_.clear();
  {
    std::lock_guard lock(reports_mutex_);
    reports_taken_.swap(reports_);
  }
  for (const auto& [id, report] : reports_taken_) {
    // This planner's own reports come back too: the fleet ignores claims of robots it owns.
    fleet_.claim(id, report.frontier);
    coordinator_.report_path(id, report.ahead);
    // Finished under another owner: not resumed from this planner's file after a restart.
    if (report.finished && !fleet_.owns(id)) goal_store_.finish(id, report.goal_id);
  }
}

void PlannerNode::apply_forgets() {
  forget_taken_.clear();
  {
    std::lock_guard lock(forget_mutex_);
    forget_taken_.swap(forget_);
  }
  for (const std::string& id : forget_taken_) {
    if (id.empty() || id == kAllRobots) continue;
    const bool known = robots_.erase(id) > 0;
    intake_.forget_robot(id);
    fleet_.forget(id);
    coordinator_.forget(id);
    missions_.forget(id);
    goal_store_.forget(id);
    waypoint_seq_.erase(id);
    reported_status_.erase(id);
    alerts_->forget_robot(id);
    // Late joiners (viewers, slamctl robots) must not get the forgotten robot's last path.
    slam::RobotPath key;
    key.robot_id(id);
    if (known && !path_writer_->dispose(key)) bump(metrics_.write_failures);
    bump(robots_forgotten_);
    spdlog::info("robot '{}' forgotten by the operator{}", id, known ? "" : " (not known here)");
  }
}

void PlannerNode::warn(const std::string& key, const std::string& line) {
  warnings_.warn(key, "{}", line);
}

}  // namespace slam::planner
