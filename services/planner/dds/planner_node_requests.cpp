// PlannerNode: what the loop does with operator input: robot goals (taken, rejected with a reason,
// kept in the goal file and resumed after a restart) and path requests (planned and answered).
#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/core/clock.hpp"
#include "planner/dds/planner_node.hpp"

namespace slam::planner {

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
  metrics_.map_version.store(static_cast<int64_t>(grid_.version()), std::memory_order_relaxed);
}

void PlannerNode::apply_uncertainties(const std::vector<RobotUncertainty>& uncertainties) {
  for (const RobotUncertainty& u : uncertainties) fleet_.observe_uncertainty(u.robot_id, u.sigma_m);
}

void PlannerNode::report_revisits() {
  fleet_.take_revisits(revisits_);
  for (const Revisit& r : revisits_) {
    bump(metrics_.revisits);
    spdlog::info(
        "robot '{}' goes back to ({:.2f}, {:.2f}) to re-localise: its pose is uncertain to {:.0f} cm",
        r.robot_id, r.place.x, r.place.y, r.sigma_m * 100.0);
  }
  revisits_.clear();
}

void PlannerNode::apply_positions(const std::vector<RobotPosition>& positions) {
  for (const RobotPosition& p : positions) {
    const std::string& id = p.robot_id;
    const Vec2 position = p.position;
    if (id.empty() || id == kAllRobots) {
      bump(metrics_.robot_positions_rejected);
      warn("position:" + id, "robot position ignored: robot_id '" + id + "' is not a robot's name");
      continue;
    }
    if (!std::isfinite(position.x) || !std::isfinite(position.y)) {
      bump(metrics_.robot_positions_rejected);
      warn("position:" + id, "robot '" + id + "': position is not finite, ignored");
      continue;
    }
    bump(metrics_.robot_positions);
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
    warn("request:" + job.client_id,
         "path request " + std::to_string(job.request_id) + " from '" + job.client_id +
             "': " + std::string(msg::plan_status_name(result.status)) + ": " + result.reason);
  }
}

}  // namespace slam::planner
