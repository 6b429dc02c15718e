// MissionEdge: NavMission samples in and out of FleetMissions.
#include "planner/dds/mission_edge.hpp"

#include "planner/dds/planner_msgs.hpp"

namespace slam::planner {

Result<ReceivedMission> to_mission(const slam::NavMission& sample, int64_t sent_ns) {
  if (static_cast<uint32_t>(sample.status()) > static_cast<uint32_t>(slam::MISSION_CANCELLED))
    return Error{"mission status " + std::to_string(static_cast<uint32_t>(sample.status())) + " is unknown"};
  msg::Mission m = msg::from_idl(sample);
  ReceivedMission out;
  out.robot_id = std::move(m.robot_id);
  out.mission.mission_id = m.mission_id;
  out.mission.loop = m.loop;
  out.mission.waypoints = std::move(m.waypoints);
  out.progress.current = m.current;
  out.progress.laps = m.laps;
  out.progress.status = m.status;
  out.progress.reason = std::move(m.reason);
  out.sent_ns = sent_ns;
  return out;
}

void fill_mission(const std::string& robot_id, const Mission& mission, const MissionProgress& progress,
                  slam::NavMission& out) {
  out.robot_id(robot_id);
  out.mission_id(mission.mission_id);
  to_points(mission.waypoints, out.waypoints());
  out.loop(mission.loop);
  out.current(static_cast<uint32_t>(progress.current));
  out.laps(progress.laps);
  out.status(msg::to_idl(progress.status));
  // The IDL bound is 256 characters.
  out.reason(progress.reason.substr(0, 255));
}

MissionEdge::MissionEdge(Counters& counters)
    : accepted_(counters.get("missions_accepted")),
      rejected_(counters.get("missions_rejected")),
      replayed_(counters.get("missions_replayed")),
      skipped_(counters.get("mission_waypoints_skipped")),
      published_(counters.get("missions_published")),
      write_failures_(counters.get("mission_write_failures")) {}

Status MissionEdge::connect(dds::Participant& participant) {
  auto writer = dds::make_writer(participant, dds::kNavMission);
  if (!writer) return writer.error();
  writer_ = std::move(*writer);
  auto reader = dds::make_reader(participant, dds::kNavMission,
                                 [this](const slam::NavMission& m, const dds::fdds::SampleInfo& info) {
                                   std::lock_guard lock(mutex_);
                                   received_.push_back(Received{m, info.source_timestamp.to_ns()});
                                 });
  if (!reader) return reader.error();
  reader_ = std::move(*reader);
  return Status::ok();
}

void MissionEdge::run(Fleet& fleet, GoalStore& store) {
  taken_.clear();
  {
    std::lock_guard lock(mutex_);
    taken_.swap(received_);
  }
  for (const Received& r : taken_) {
    const std::string id = r.sample.robot_id().to_string();
    auto mission = to_mission(r.sample, r.sent_ns);
    auto receipt =
        mission ? missions_.receive(*mission, fleet, store) : Result<FleetMissions::Receipt>(mission.error());
    if (!receipt) {
      reject(r.sample, receipt.message());
      continue;
    }
    if (*receipt == FleetMissions::Receipt::Replayed) {
      bump(replayed_);
      spdlog::debug("mission {} for robot '{}' is not newer than the stored goal or mission; ignored",
                    r.sample.mission_id(), id);
    } else if (*receipt == FleetMissions::Receipt::Started) {
      bump(accepted_);
      spdlog::info("mission {} for robot '{}': {} waypoint(s){}, from waypoint {}", r.sample.mission_id(), id,
                   r.sample.waypoints().size(), r.sample.loop() ? ", looped" : "", r.sample.current());
    }
  }
  for (const std::string& id : missions_.step(fleet)) {
    bump(skipped_);
    if (const MissionRunner::Running* m = missions_.runner().find(id))
      warnings_.warn("skip:" + id, "robot '{}' mission {}: {}", id, m->mission.mission_id,
                     m->progress.reason);
  }
  missions_.take_changed(fleet, store, publish_);
  for (const std::string& id : publish_) publish(id);
}

void MissionEdge::publish(const std::string& robot_id) {
  const MissionRunner::Running* m = missions_.runner().find(robot_id);
  if (m == nullptr) return;
  if (m->progress.status == MissionStatus::Done) {
    spdlog::info("robot '{}' finished mission {}", robot_id, m->mission.mission_id);
  } else if (m->progress.status == MissionStatus::Failed) {
    warnings_.warn("failed:" + robot_id, "robot '{}' failed mission {}: {}", robot_id, m->mission.mission_id,
                   m->progress.reason);
  }
  fill_mission(robot_id, m->mission, m->progress, out_);
  bump(writer_ && writer_->write(out_) ? published_ : write_failures_);
}

void MissionEdge::reject(const slam::NavMission& sample, const std::string& reason) {
  bump(rejected_);
  const std::string id = sample.robot_id().to_string();
  warnings_.warn("mission:" + id, "mission {} for robot '{}' rejected: {}", sample.mission_id(), id, reason);
  // The mission's own topic is where its outcome is read: say there why this one did not start.
  if (id.empty() || id.size() > 64 || sample.status() != slam::MISSION_ACTIVE) return;
  out_ = sample;
  out_.status(slam::MISSION_FAILED);
  out_.reason(reason.substr(0, 255));
  bump(writer_ && writer_->write(out_) ? published_ : write_failures_);
}

}  // namespace slam::planner
