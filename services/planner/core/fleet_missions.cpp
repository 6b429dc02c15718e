// FleetMissions: missions received, resumed, moved on and kept.
#include "planner/core/fleet_missions.hpp"

namespace slam::planner {

size_t FleetMissions::resume(const GoalRecord& record, Fleet& fleet) {
  size_t resumed = 0;
  for (const StoredMission& m : missions_to_resume(record)) {
    if (!validate(m.mission, m.progress)) continue;  // parse_goal_record checked it already
    if (!fleet.set_goal(m.robot_id, runner_.start(m.robot_id, m.mission, m.progress))) continue;
    sent_ns_[m.robot_id] = m.sent_ns;
    ++resumed;
  }
  // Resuming changes nothing to keep or report.
  runner_.take_changed();
  return resumed;
}

Result<FleetMissions::Receipt> FleetMissions::receive(const ReceivedMission& received, Fleet& fleet,
                                                      GoalStore& store) {
  const std::string& id = received.robot_id;
  if (id.empty() || id == kAllRobots) return Error{"a mission is for one robot, not '" + id + "'"};
  SLAM_TRY(validate(received.mission, received.progress));
  const MissionRunner::Running* running = runner_.find(id);
  if (running != nullptr && running->mission.mission_id == received.mission.mission_id) {
    // The owner moves the mission on itself; its own reports come back here too.
    if (fleet.owns(id)) return Receipt::Ignored;
    if (const auto leg = runner_.adopt(id, received.progress)) SLAM_TRY(fleet.set_goal(id, *leg));
    return Receipt::Adopted;
  }
  // An ended mission (cancelled, done, rejected) has nothing to start.
  if (received.progress.status != MissionStatus::Active) return Receipt::Ignored;
  if (store.is_stale(id, received.sent_ns)) return Receipt::Replayed;
  const Goal leg = leg_goal(received.mission, received.progress);
  SLAM_TRY(fleet.set_goal(id, leg));
  runner_.start(id, received.mission, received.progress);
  sent_ns_[id] = received.sent_ns;
  return Receipt::Started;
}

void FleetMissions::forget(const std::string& robot_id) {
  runner_.forget(robot_id);
  sent_ns_.erase(robot_id);
}

void FleetMissions::goal_accepted(const std::string& robot_id) {
  if (robot_id == kAllRobots) {
    runner_.cancel_all();
  } else {
    runner_.cancel(robot_id);
  }
}

std::vector<std::string> FleetMissions::step(Fleet& fleet) {
  std::vector<std::string> skipped;
  std::vector<std::pair<std::string, Goal>> next;
  for (const auto& [id, running] : runner_.missions()) {
    if (running.progress.status != MissionStatus::Active || !fleet.owns(id)) continue;
    const GoalTracker* t = fleet.tracker(id);
    // Only the mission's own leg counts: a goal that replaced it is not its outcome.
    if (t == nullptr || t->goal().goal_id != running.mission.mission_id) continue;
    if (t->status() != GoalStatus::Reached && t->status() != GoalStatus::Failed) continue;
    const bool reached = t->status() == GoalStatus::Reached;
    if (!reached) skipped.push_back(id);
    const std::string reason = t->reason();
    if (const auto leg = runner_.leg_ended(id, reached, reason)) next.emplace_back(id, *leg);
  }
  // The leg goals are valid by construction (finite waypoints): set_goal cannot refuse them.
  for (const auto& [id, leg] : next) (void)fleet.set_goal(id, leg);
  return skipped;
}

void FleetMissions::take_changed(const Fleet& fleet, GoalStore& store, std::vector<std::string>& publish) {
  publish.clear();
  for (const std::string& id : runner_.take_changed()) {
    const MissionRunner::Running* r = runner_.find(id);
    if (r == nullptr) continue;
    store.put_mission(StoredMission{id, r->mission, r->progress, sent_ns_[id]});
    if (fleet.owns(id) || fleet.tracker(id) == nullptr) publish.push_back(id);
  }
}

}  // namespace slam::planner
