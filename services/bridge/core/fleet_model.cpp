// The fleet as the bridge knows it (see fleet_model.hpp).
#include "bridge/core/fleet_model.hpp"

#include <utility>

namespace slam::bridge {

void PointRing::add(Vec2 p) {
  if (capacity_ == 0) return;
  if (points_.size() < capacity_) {
    points_.push_back(p);
    return;
  }
  points_[next_] = p;
  next_ = (next_ + 1) % capacity_;
}

RobotView& FleetModel::robot(const std::string& id) {
  return robots_.try_emplace(id, points_per_robot_).first->second;
}

void FleetModel::ingest(const msg::RobotPose& s) {
  if (state_stamps_.judge(s.robot_id, s.last_seen_ns) != LatestStamps::Verdict::Fresh) return;
  forgotten_.erase(s.robot_id);
  RobotView& r = robot(s.robot_id);
  r.state = s;
  r.has_state = true;
  ++versions_.robots;
}

void FleetModel::ingest(msg::RobotPath&& p) {
  if (forgotten_.contains(p.robot_id)) return;
  RobotView& r = robot(p.robot_id);
  r.path = std::move(p);
  r.has_path = true;
  ++versions_.paths;
}

void FleetModel::ingest(const ObservationInput& o) {
  if (o.hits.empty() || forgotten_.contains(o.robot_id)) return;
  RobotView& r = robot(o.robot_id);
  for (const Vec2& hit : o.hits) r.points.add(hit);
  ++versions_.points;
}

void FleetModel::forget(const std::string& robot_id) {
  state_stamps_.forget(robot_id);
  forgotten_.insert(robot_id);
  if (robots_.erase(robot_id) == 0) return;
  ++versions_.robots;
  ++versions_.paths;
  ++versions_.points;
}

void FleetModel::ingest(msg::Heartbeat&& h, int64_t now_mono_ns) {
  ServiceView& s = services_[{h.service, h.instance_id}];
  s.beat = std::move(h);
  s.heard_ns = now_mono_ns;
  ++versions_.health;
}

void FleetModel::ingest(msg::Alert&& a) {
  std::string id = a.alert_id;
  alerts_[std::move(id)] = std::move(a);
  ++versions_.alerts;
}

}  // namespace slam::bridge
