// Locked hand-over from listener threads to the render thread (see intake.hpp).
#include "viewer/core/intake.hpp"

#include <utility>

namespace slam::viewer {

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

void Intake::push(msg::GridSnapshot&& s) {
  std::lock_guard lock(mutex_);
  pending_.snapshot = std::move(s);
  pending_.patches.clear();  // the snapshot includes them, or they belong to an older layout
}

void Intake::push(msg::GridTiles&& p) {
  std::lock_guard lock(mutex_);
  pending_.patches.push_back(std::move(p));
}

void Intake::push(ObservationData&& o) {
  std::lock_guard lock(mutex_);
  pending_.observations.push_back(std::move(o));
}

void Intake::push(msg::RobotState&& s) {
  std::lock_guard lock(mutex_);
  for (auto& old : pending_.states)
    if (old.robot_id == s.robot_id) {
      old = std::move(s);
      return;
    }
  pending_.states.push_back(std::move(s));
}

void Intake::push(msg::RobotPose&& p) {
  std::lock_guard lock(mutex_);
  pending_.poses.push_back(std::move(p));
}

void Intake::push(msg::RobotPath&& p) {
  std::lock_guard lock(mutex_);
  for (auto& old : pending_.paths)
    if (old.robot_id == p.robot_id) {
      old = std::move(p);
      return;
    }
  pending_.paths.push_back(std::move(p));
}

void Intake::push(msg::Mission&& m) {
  std::lock_guard lock(mutex_);
  for (auto& old : pending_.missions)
    if (old.robot_id == m.robot_id) {
      old = std::move(m);
      return;
    }
  pending_.missions.push_back(std::move(m));
}

void Intake::push(msg::PoseCorrection&& c) {
  std::lock_guard lock(mutex_);
  for (auto& old : pending_.corrections)
    if (old.robot_id == c.robot_id) {
      old = std::move(c);
      return;
    }
  pending_.corrections.push_back(std::move(c));
}

void Intake::push(msg::Heartbeat&& h) {
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

void Intake::push(msg::Alert&& a) {
  std::lock_guard lock(mutex_);
  pending_.alerts.push_back(std::move(a));
}

void Intake::push(ForgetData&& f) {
  std::lock_guard lock(mutex_);
  pending_.forgets.push_back(std::move(f));
}

void Intake::push(msg::PathReply&& r) {
  std::lock_guard lock(mutex_);
  pending_.path_replies.push_back(std::move(r));
}

void Intake::drain(IntakeBatch& out) {
  out.clear();
  std::lock_guard lock(mutex_);
  std::swap(out, pending_);
}

}  // namespace slam::viewer
