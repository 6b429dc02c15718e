// RobotRegistry: first sight, presence transitions and per-robot counters.
#include "gateway/core/robot_registry.hpp"

#include <utility>

namespace slam::gateway {

std::string_view protocol_name(Protocol protocol) {
  switch (protocol) {
    case Protocol::V1:
      return "v1";
    case Protocol::V2:
      return "v2";
    case Protocol::Vda5050:
      return "vda5050";
  }
  return "unknown";
}

RobotRegistry::RobotRegistry(RegistryConfig config) : config_(config) {}

RobotRecord* RobotRegistry::lookup(std::string_view id) {
  auto it = robots_.find(id);
  return it == robots_.end() ? nullptr : &it->second;
}

const RobotRecord* RobotRegistry::find(std::string_view id) const {
  auto it = robots_.find(id);
  return it == robots_.end() ? nullptr : &it->second;
}

std::optional<Protocol> RobotRegistry::protocol_of(std::string_view id) const {
  const RobotRecord* r = find(id);
  if (!r) return std::nullopt;
  return r->protocol;
}

RobotRecord* RobotRegistry::touch(std::string_view id, Protocol protocol, Instant now, AcceptResult& result) {
  RobotRecord* r = lookup(id);
  if (!r) {
    if (robots_.size() >= config_.max_robots) {
      result.kind = AcceptResult::Kind::RegistryFull;
      return nullptr;
    }
    std::string key(id);
    RobotRecord fresh;
    fresh.id = key;
    fresh.presence = Presence::Offline;  // set_presence() brings it online and counts it
    fresh.first_seen_ns = now.wall_ns;
    r = &robots_.emplace(std::move(key), std::move(fresh)).first->second;
    result.first_seen = true;
  }
  r->protocol = protocol;
  r->last_seen_ns = now.wall_ns;
  r->last_heard_mono_ns = now.mono_ns;
  ++r->messages;
  r->changed = true;
  return r;
}

void RobotRegistry::set_presence(RobotRecord& r, Presence presence, AcceptResult& result) {
  if (r.presence == presence) return;
  r.presence = presence;
  r.urgent = true;
  if (presence == Presence::Online) {
    ++online_;
    result.came_online = !result.first_seen;
  } else {
    --online_;
    result.went_offline = true;
  }
}

AcceptResult RobotRegistry::accept_observation(std::string_view id, Protocol protocol,
                                               protocol::DecodedObservation& observation, Instant now) {
  AcceptResult result;
  if (!observation.has_pose) {
    const RobotRecord* known = find(id);
    if (!known || !known->has_pose) {
      result.kind = AcceptResult::Kind::NoPose;
      return result;
    }
    // Rays start where the robot last said it was (docs/protocol.md, v2 points).
    observation.x = known->x;
    observation.y = known->y;
    observation.theta = known->theta;
    observation.has_heading = known->has_heading;
    observation.has_pose = true;
  }
  RobotRecord* r = touch(id, protocol, now, result);
  if (!r) return result;
  set_presence(*r, Presence::Online, result);
  r->has_pose = true;
  r->x = observation.x;
  r->y = observation.y;
  r->theta = observation.has_heading ? observation.theta : 0.0;
  r->has_heading = observation.has_heading;
  r->points += observation.hits.size() + observation.misses.size();
  result.seq = ++r->observation_seq;
  return result;
}

AcceptResult RobotRegistry::accept_status(std::string_view id, const protocol::DecodedStatus& status,
                                          Instant now, Protocol protocol) {
  AcceptResult result;
  RobotRecord* r = touch(id, protocol, now, result);
  if (!r) return result;
  r->battery = status.battery;
  r->status = status.state;
  set_presence(*r, status.offline ? Presence::Offline : Presence::Online, result);
  return result;
}

void RobotRegistry::set_status(std::string_view id, const protocol::DecodedStatus& status) {
  RobotRecord* r = lookup(id);
  if (!r) return;
  r->battery = status.battery;
  r->status = status.state;
  r->changed = true;
}

bool RobotRegistry::forget(std::string_view id) {
  const auto it = robots_.find(id);
  if (it == robots_.end()) return false;
  if (it->second.presence == Presence::Online) --online_;
  robots_.erase(it);
  return true;
}

void RobotRegistry::count_rejected(std::string_view id) {
  RobotRecord* r = lookup(id);
  if (!r) return;
  ++r->rejected;
  r->changed = true;
}

void RobotRegistry::expire(Instant now, const std::function<void(const RobotRecord&)>& on_offline) {
  for (auto& [id, r] : robots_) {
    if (r.presence != Presence::Online || now.mono_ns - r.last_heard_mono_ns < config_.offline_after_ns)
      continue;
    r.presence = Presence::Offline;
    r.changed = true;
    r.urgent = true;
    --online_;
    if (on_offline) on_offline(r);
  }
}

void RobotRegistry::mark_changed(std::string_view id) {
  if (RobotRecord* r = lookup(id)) r->changed = true;
}

void RobotRegistry::take_changed(const std::function<void(const RobotRecord&)>& fn, bool urgent_only) {
  for (auto& [id, r] : robots_) {
    if (!r.changed || (urgent_only && !r.urgent)) continue;
    r.changed = false;
    r.urgent = false;
    fn(r);
  }
}

void RobotRegistry::for_each(const std::function<void(const RobotRecord&)>& fn) const {
  for (const auto& [id, r] : robots_) fn(r);
}

}  // namespace slam::gateway
