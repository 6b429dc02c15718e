// FleetDigestBuilder: per-robot rings of hits, registry copies, frame placement.
#include "gateway/core/fleet_digest.hpp"

namespace slam::gateway {

void FleetDigestBuilder::add_hits(std::string_view id, std::span<const protocol::Point> hits,
                                  std::int64_t stamp_ns) {
  if (hits.empty() || points_per_robot_ == 0) return;
  auto it = pending_.find(id);
  if (it == pending_.end()) {
    it = pending_.emplace(std::string(id), Pending{}).first;
    it->second.ring.reserve(points_per_robot_);
  }
  Pending& p = it->second;
  // Only the last points_per_robot_ of a large observation can stay in the ring.
  if (hits.size() > points_per_robot_) hits = hits.last(points_per_robot_);
  for (const protocol::Point& h : hits) {
    const Vec2 v{h.x, h.y};
    if (p.ring.size() < points_per_robot_) {
      p.ring.push_back(v);
    } else {
      p.ring[p.next] = v;
      p.next = (p.next + 1) % points_per_robot_;
    }
  }
  p.stamp_ns = stamp_ns;
}

void FleetDigestBuilder::forget(std::string_view id) {
  if (auto it = pending_.find(id); it != pending_.end()) pending_.erase(it);
}

void FleetDigestBuilder::collect(const RobotRegistry& registry) {
  robot_count_ = 0;
  registry.for_each([this](const RobotRecord& r) {
    if (robot_count_ == robots_.size()) robots_.emplace_back();
    DigestRobotEntry& e = robots_[robot_count_++];
    e.id.assign(r.id);
    e.pose = {r.x, r.y, r.theta};
    e.has_pose = r.has_pose;
    e.has_heading = r.has_heading;
    e.online = r.presence == Presence::Online;
    e.last_seen_ns = r.last_seen_ns;
  });
}

void FleetDigestBuilder::take_points() {
  taken_count_ = 0;
  for (auto& [id, p] : pending_) {
    if (p.ring.empty()) continue;
    if (taken_count_ == taken_.size()) taken_.emplace_back();
    DigestPointsEntry& e = taken_[taken_count_++];
    e.id.assign(id);
    e.stamp_ns = p.stamp_ns;
    e.points.assign(p.ring.begin(), p.ring.end());
    p.ring.clear();
    p.next = 0;
  }
}

void FleetDigestBuilder::place_robots(const CorrectionTable& corrections) {
  for (std::size_t i = 0; i < robot_count_; ++i) {
    DigestRobotEntry& e = robots_[i];
    // A robot heard only through status messages has no pose to place in the map.
    if (e.has_pose) e.pose = to_map_frame(corrections.of(e.id).map_from_odom, e.pose, e.has_heading);
  }
}

void FleetDigestBuilder::place_points(const CorrectionTable& corrections) {
  for (std::size_t i = 0; i < taken_count_; ++i) {
    DigestPointsEntry& e = taken_[i];
    const Pose map_from_odom = corrections.of(e.id).map_from_odom;
    for (Vec2& p : e.points) p = map_from_odom.transform(p);
  }
}

}  // namespace slam::gateway
