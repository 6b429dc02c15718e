// Locked hand-over from listener threads to the render thread (see intake.hpp).
#include "viewer/core/intake.hpp"

#include <utility>

namespace slam::viewer {

const char* goal_mode_name(GoalMode m) {
  switch (m) {
    case GoalMode::Idle:
      return "idle";
    case GoalMode::Direct:
      return "direct";
    case GoalMode::Planned:
      return "planned";
    case GoalMode::Square:
      return "square";
    case GoalMode::Explore:
      return "explore";
    case GoalMode::Home:
      return "home";
    case GoalMode::Stop:
      return "stop";
  }
  return "?";
}

const char* goal_status_name(GoalStatus s) {
  switch (s) {
    case GoalStatus::None:
      return "none";
    case GoalStatus::Active:
      return "active";
    case GoalStatus::Reached:
      return "reached";
    case GoalStatus::Failed:
      return "failed";
  }
  return "?";
}

const char* correction_source_name(CorrectionSource s) {
  switch (s) {
    case CorrectionSource::Identity:
      return "identity";
    case CorrectionSource::Match:
      return "match";
    case CorrectionSource::Loop:
      return "loop closure";
    case CorrectionSource::Operator:
      return "operator";
    case CorrectionSource::Restored:
      return "restored";
  }
  return "?";
}

const char* mission_status_name(MissionStatus s) {
  switch (s) {
    case MissionStatus::Active:
      return "active";
    case MissionStatus::Done:
      return "done";
    case MissionStatus::Failed:
      return "failed";
    case MissionStatus::Cancelled:
      return "cancelled";
  }
  return "?";
}

void IntakeBatch::clear() {
  snapshot.reset();
  patches.clear();
  observations.clear();
  states.clear();
  poses.clear();
  paths.clear();
  missions.clear();
  corrections.clear();
  heartbeats.clear();
  mqtt.clear();
  subscriptions.reset();
  world.reset();
  truth.reset();
  replies.clear();
  mqtt_replies.clear();
  sim_replies.clear();
  alerts.clear();
  forgets.clear();
  path_replies.clear();
  mqtt_dropped = 0;
}

void Intake::push(GridSnapshotData&& s) {
  std::lock_guard lock(mutex_);
  pending_.snapshot = std::move(s);
  pending_.patches.clear();  // the snapshot includes them, or they belong to an older layout
}

void Intake::push(GridPatchData&& p) {
  std::lock_guard lock(mutex_);
  pending_.patches.push_back(std::move(p));
}

void Intake::push(ObservationData&& o) {
  std::lock_guard lock(mutex_);
  pending_.observations.push_back(std::move(o));
}

void Intake::push(RobotStateData&& s) {
  std::lock_guard lock(mutex_);
  for (auto& old : pending_.states)
    if (old.robot_id == s.robot_id) {
      old = std::move(s);
      return;
    }
  pending_.states.push_back(std::move(s));
}

void Intake::push(RobotPoseData&& p) {
  std::lock_guard lock(mutex_);
  pending_.poses.push_back(std::move(p));
}

void Intake::push(RobotPathData&& p) {
  std::lock_guard lock(mutex_);
  for (auto& old : pending_.paths)
    if (old.robot_id == p.robot_id) {
      old = std::move(p);
      return;
    }
  pending_.paths.push_back(std::move(p));
}

void Intake::push(MissionData&& m) {
  std::lock_guard lock(mutex_);
  for (auto& old : pending_.missions)
    if (old.robot_id == m.robot_id) {
      old = std::move(m);
      return;
    }
  pending_.missions.push_back(std::move(m));
}

void Intake::push(PoseCorrectionData&& c) {
  std::lock_guard lock(mutex_);
  for (auto& old : pending_.corrections)
    if (old.robot_id == c.robot_id) {
      old = std::move(c);
      return;
    }
  pending_.corrections.push_back(std::move(c));
}

void Intake::push(HeartbeatData&& h) {
  std::lock_guard lock(mutex_);
  pending_.heartbeats.push_back(std::move(h));
}

void Intake::push(MqttEntry&& e) {
  std::lock_guard lock(mutex_);
  if (pending_.mqtt.size() >= max_pending_mqtt_) {
    pending_.mqtt.erase(pending_.mqtt.begin());
    ++pending_.mqtt_dropped;
  }
  pending_.mqtt.push_back(std::move(e));
}

void Intake::push(MqttSubscriptionsData&& s) {
  std::lock_guard lock(mutex_);
  pending_.subscriptions = std::move(s);
}

void Intake::push(SimWorldData&& w) {
  std::lock_guard lock(mutex_);
  pending_.world = std::move(w);
}

void Intake::push(SimTruthData&& t) {
  std::lock_guard lock(mutex_);
  pending_.truth = std::move(t);
}

void Intake::push(MapReplyData&& r) {
  std::lock_guard lock(mutex_);
  pending_.replies.push_back(std::move(r));
}

void Intake::push(MqttReplyData&& r) {
  std::lock_guard lock(mutex_);
  pending_.mqtt_replies.push_back(std::move(r));
}

void Intake::push(SimReplyData&& r) {
  std::lock_guard lock(mutex_);
  pending_.sim_replies.push_back(std::move(r));
}

void Intake::push(AlertData&& a) {
  std::lock_guard lock(mutex_);
  pending_.alerts.push_back(std::move(a));
}

void Intake::push(ForgetData&& f) {
  std::lock_guard lock(mutex_);
  pending_.forgets.push_back(std::move(f));
}

void Intake::push(PathReplyData&& r) {
  std::lock_guard lock(mutex_);
  pending_.path_replies.push_back(std::move(r));
}

void Intake::drain(IntakeBatch& out) {
  out.clear();
  std::lock_guard lock(mutex_);
  std::swap(out, pending_);
}

}  // namespace slam::viewer
