// PlannerNode: configure, and the loop pass that turns intake into core calls and samples.
#include "planner/planner_node.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <utility>

#include "common/core/clock.hpp"
#include "common/core/service_identity.hpp"

namespace slam::planner {

namespace {

std::string counter_name(PlanStatus status) {
  std::string name = "replies_";
  for (char c : to_string(status)) name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
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
      robot_states(c.get("robot_states")),
      robot_states_rejected(c.get("robot_states_rejected")),
      snapshots(c.get("snapshots")),
      snapshots_rejected(c.get("snapshots_rejected")),
      patches_applied(c.get("patches_applied")),
      patches_skipped(c.get("patches_skipped")),
      write_failures(c.get("write_failures")),
      path_requests_not_owned(c.get("path_requests_not_owned")),
      robots_owned(c.get("robots_owned")),
      planners_live(c.get("planners_live")),
      robots_held(c.get("robots_held")),
      deadlocks_broken(c.get("deadlocks_broken")),
      replans_around_robots(c.get("replans_around_robots")),
      longest_wait_ms(c.get("longest_wait_ms")) {
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
  auto states = dds::make_reader(*participant_, dds::kRobotState,
                                 [this](const slam::RobotState& s, const auto&) { intake_.push_state(s); });
  if (!states) return states.error();
  state_reader_ = std::move(*states);
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
  apply_states(batch_.states);
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
  coordinate(now);
  publish_paths();
  stream_waypoints(now);
  flush_store();
}

void PlannerNode::resume_goals() {
  const GoalRecord& record = goal_store_.record();
  for (const auto& [id, home] : record.homes) fleet_.restore_home(id, home);
  size_t resumed = 0;
  for (const StoredGoal& g : goals_to_resume(record)) {
    if (auto started = fleet_.set_goal(g.robot_id, g.goal); !started) {
      warn("resume:" + g.robot_id, "stored goal " + std::to_string(g.goal.goal_id) + " for robot '" +
                                       g.robot_id + "' not resumed: " + started.message());
      continue;
    }
    ++resumed;
  }
  const size_t missions = missions_.resume(record, fleet_);
  if (!options_.goal_store.empty()) {
    spdlog::info("goal store {}: {} goal(s) and {} mission(s) resumed, {} home(s) known", options_.goal_store,
                 resumed, missions, record.homes.size());
  }
}

void PlannerNode::store_goal(const std::string& robot_id, const Goal& goal, int64_t sent_ns) {
  goal_store_.put(StoredGoal{robot_id, goal, sent_ns, false});
  if (robot_id != kAllRobots) return;
  for (const std::string& id : robots_) goal_store_.put(StoredGoal{id, goal, sent_ns, false});
}

void PlannerNode::flush_store() {
  if (!goal_store_.dirty()) return;
  if (auto s = goal_store_.flush(); !s) {
    bump(metrics_.store_failures);
    warn("store", s.message() + "; goals will not survive a restart until it can be written");
  }
}

void PlannerNode::apply_grid(IntakeBatch& batch) {
  if (batch.snapshot) {
    const uint32_t previous_layout = grid_.layout_id();
    const bool first = grid_.empty();
    if (auto s = apply_snapshot(*batch.snapshot, grid_); !s) {
      bump(metrics_.snapshots_rejected);
      warn("snapshot", "grid snapshot ignored: " + s.message());
    } else {
      bump(metrics_.snapshots);
      awaiting_snapshot_ = false;
      fleet_.grid_changed(grid_, std::nullopt);
      if (first || grid_.layout_id() != previous_layout) {
        const GridGeometry& g = grid_.geometry();
        spdlog::info("grid layout {}: {}x{} cells of {} m, origin ({}, {}), version {}", grid_.layout_id(),
                     g.width, g.height, g.resolution, g.origin.x, g.origin.y, grid_.version());
      }
    }
  }
  if (batch.patches_dropped && !awaiting_snapshot_) {
    awaiting_snapshot_ = true;
    warn("patch", "grid patches arrived faster than the loop applies them; waiting for the next snapshot");
  }
  for (const slam::GridTiles& patch : batch.patches) {
    if (grid_.empty() || awaiting_snapshot_) {
      bump(metrics_.patches_skipped);
      continue;
    }
    // Already contained in the snapshot that overtook it.
    if (patch.layout_id() == grid_.layout_id() && patch.version() <= grid_.version()) continue;
    changed_tiles_.clear();
    if (auto s = apply_patch(patch, grid_, changed_tiles_); !s) {
      bump(metrics_.patches_skipped);
      awaiting_snapshot_ = true;
      warn("patch", s.message() + "; waiting for the next snapshot");
      continue;
    }
    bump(metrics_.patches_applied);
    fleet_.grid_changed(grid_, changed_tiles_);
  }
}

void PlannerNode::apply_states(const std::vector<slam::RobotState>& states) {
  for (const slam::RobotState& s : states) {
    const std::string id = s.robot_id().to_string();
    const Vec2 position{s.pose().x(), s.pose().y()};
    if (id.empty() || id == kAllRobots) {
      bump(metrics_.robot_states_rejected);
      warn("state:" + id, "robot state ignored: robot_id '" + id + "' is not a robot's name");
      continue;
    }
    if (!std::isfinite(position.x) || !std::isfinite(position.y)) {
      bump(metrics_.robot_states_rejected);
      warn("state:" + id, "robot '" + id + "': position is not finite, state ignored");
      continue;
    }
    bump(metrics_.robot_states);
    const bool first = robots_.insert(id).second;
    fleet_.observe(id, position);
    coordinator_.observe(id, position);
    if (!first) continue;
    if (const auto home = fleet_.home(id)) goal_store_.put_home(id, *home);
    const GoalTracker* t = fleet_.tracker(id);
    if (t != nullptr && t->status() == GoalStatus::Active) {
      spdlog::info("robot '{}' first seen at ({}, {}); starts goal {} (mode {})", id, position.x, position.y,
                   t->goal().goal_id, static_cast<uint32_t>(t->mode()));
    } else {
      spdlog::info("robot '{}' first seen at ({}, {})", id, position.x, position.y);
    }
  }
}

void PlannerNode::apply_goals(const std::vector<ReceivedGoal>& goals) {
  for (const ReceivedGoal& received : goals) {
    const slam::NavGoal& sample = received.sample;
    const std::string id = sample.robot_id().to_string();
    // After a restart, writers' caches replay goals the store already resumed (or replaced).
    if (goal_store_.is_stale(id, received.sent_ns)) {
      bump(metrics_.goals_replayed);
      spdlog::debug("goal {} for robot '{}' is not newer than the stored one; ignored", sample.goal_id(), id);
      continue;
    }
    auto command = to_goal(sample);
    if (!command) {
      reject_goal(id, sample, command.message());
      continue;
    }
    auto started = fleet_.set_goal(command->robot_id, command->goal);
    if (!started) {
      reject_goal(id, sample, started.message());
      continue;
    }
    bump(metrics_.goals_accepted);
    missions_.goal_accepted(command->robot_id);
    store_goal(command->robot_id, command->goal, received.sent_ns);
    spdlog::info("goal {} (mode {}) for robot '{}' ({} robot(s) now), target ({}, {})", sample.goal_id(),
                 static_cast<uint32_t>(sample.mode()), id, *started, sample.target().x(),
                 sample.target().y());
    if (id != kAllRobots && *started == 0) report_waiting(id, sample);
  }
}

void PlannerNode::report_waiting(const std::string& robot_id, const slam::NavGoal& sample) {
  // The robot path is where a goal's outcome is read: say there that this one waits for its robot.
  slam::RobotPath out;
  out.robot_id(robot_id);
  out.goal_id(sample.goal_id());
  out.mode(sample.mode());
  out.status(slam::GOAL_STATUS_NONE);
  out.target(sample.target());
  out.reason("unknown robot '" + robot_id + "': the goal starts when it first reports its position");
  bump(path_writer_->write(out) ? metrics_.paths_published : metrics_.write_failures);
}

void PlannerNode::reject_goal(const std::string& robot_id, const slam::NavGoal& sample,
                              const std::string& reason) {
  bump(metrics_.goals_rejected);
  warn("goal:" + robot_id,
       "goal " + std::to_string(sample.goal_id()) + " for robot '" + robot_id + "' rejected: " + reason);
  // The robot path is where a goal's outcome is read: say there why this one did not start.
  std::vector<std::string> targets;
  if (robot_id == kAllRobots) {
    targets.assign(robots_.begin(), robots_.end());
  } else if (!robot_id.empty()) {
    targets.push_back(robot_id);
  }
  for (const std::string& id : targets) {
    slam::RobotPath out;
    out.robot_id(id);
    out.goal_id(sample.goal_id());
    out.mode(static_cast<uint32_t>(sample.mode()) <= static_cast<uint32_t>(slam::GOAL_STOP)
                 ? sample.mode()
                 : slam::GOAL_IDLE);
    out.status(slam::GOAL_STATUS_FAILED);
    out.target(sample.target());
    out.reason(reason);
    bump(path_writer_->write(out) ? metrics_.paths_published : metrics_.write_failures);
  }
}

void PlannerNode::submit_requests(const std::vector<slam::PathRequest>& requests) {
  if (requests.empty()) return;
  if (grid_.revision() != handed_revision_) {
    workers_->set_grid(std::make_shared<const PlanningGrid>(grid_));
    handed_revision_ = grid_.revision();
  }
  for (const slam::PathRequest& r : requests) {
    {
      // Every planner receives every request; only the owner of its id answers it.
      std::lock_guard lock(ownership_mutex_);
      if (!ownership_.owns(std::to_string(r.request_id()), monotonic_ns())) {
        bump(metrics_.path_requests_not_owned);
        continue;
      }
    }
    // A requester's retry: planned once, answered again from the cache (or by the running job).
    const auto verdict = replies_sent_.admit(r.request_id());
    if (verdict.admission != Admission::Execute) {
      bump(metrics_.path_requests_repeated);
      if (verdict.reply && !reply_writer_->write(*verdict.reply)) bump(metrics_.write_failures);
      continue;
    }
    bump(metrics_.path_requests);
    workers_->submit(to_job(r));
  }
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
    command_.waypoint(to_point(d.waypoint));
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
  PathReport report = to_report(sample);
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

void PlannerNode::reply(const PathJob& job, const PlanResult& result) {
  slam::PathReply out;
  fill_reply(job, result, out);
  replies_sent_.complete(job.request_id, out);
  if (!reply_writer_->write(out)) bump(metrics_.write_failures);
  bump(*metrics_.replies[static_cast<size_t>(result.status)]);
  if (result.ok()) {
    spdlog::debug("path request {} from '{}': {} m in {} s", job.request_id, job.client_id, result.length_m,
                  result.planning_time_s);
  } else {
    warn("request:" + job.client_id, "path request " + std::to_string(job.request_id) + " from '" +
                                         job.client_id + "': " + std::string(to_string(result.status)) +
                                         ": " + result.reason);
  }
}

void PlannerNode::warn(const std::string& key, const std::string& line) {
  warnings_.warn(key, "{}", line);
}

}  // namespace slam::planner
