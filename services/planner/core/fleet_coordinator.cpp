// FleetCoordinator: the traffic rules (traffic_rules.hpp) applied to the fleet's waypoint commands.
#include "planner/core/fleet_coordinator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "planner/core/traffic_geometry.hpp"

namespace slam::planner {
namespace {

constexpr double kResendMoveM = 0.05;  // a hold moved further than this is sent again

// FNV-1a: the same tie-break number for a robot on every planner.
uint32_t stable_hash(const std::string& s) {
  uint32_t h = 2166136261u;
  for (unsigned char c : s) h = (h ^ c) * 16777619u;
  return h;
}

}  // namespace

FleetCoordinator::FleetCoordinator(const CoordinationConfig& config) : config_(config), rules_(config) {}

size_t FleetCoordinator::slot(const std::string& robot_id) {
  const auto [it, inserted] = slots_.try_emplace(robot_id, robots_.size());
  if (inserted) {
    robots_.emplace_back();
    robots_.back().id = robot_id;
  }
  return it->second;
}

void FleetCoordinator::observe(const std::string& robot_id, Vec2 position) {
  Slot& s = robots_[slot(robot_id)];
  s.position = position;
  s.seen = true;
}

void FleetCoordinator::forget(const std::string& robot_id) {
  const auto it = slots_.find(robot_id);
  if (it == slots_.end()) return;
  robots_[it->second].seen = false;
  robots_[it->second].reported.clear();
}

void FleetCoordinator::report_path(const std::string& robot_id, std::span<const Vec2> ahead) {
  Slot& s = robots_[slot(robot_id)];
  s.reported.assign(ahead.begin(), ahead.end());
}

void FleetCoordinator::coordinate(Fleet& fleet, const PlanningGrid& grid, int64_t now_ns) {
  inputs_.clear();
  for (Slot& s : robots_) {
    std::span<const Vec2> ahead;
    uint64_t goal_id = 0;
    if (const GoalTracker* t = fleet.tracker(s.id); t != nullptr && s.seen) {
      goal_id = t->goal().goal_id;
      if (fleet.owns(s.id)) {
        if (t->status() == GoalStatus::Active && t->current_waypoint()) ahead = t->remaining();
      } else {
        ahead = s.reported;
      }
    }
    // A route starts when the robot gets one, or another goal or destination: it queues anew.
    const Vec2 target = ahead.empty() ? Vec2{} : ahead.back();
    const bool active = !ahead.empty();
    if (active && (!s.active || goal_id != s.goal_id || distance(target, s.target) > 1e-6))
      s.route_since_ns = now_ns;
    s.active = active;
    s.goal_id = goal_id;
    s.target = target;
    // A robot not seen yet stands nowhere: far off, without a route, it meets no one.
    const Vec2 position = s.seen ? s.position : Vec2{std::numeric_limits<double>::max() / 4, 0.0};
    inputs_.push_back(TrafficRobot{position, ahead, s.route_since_ns, stable_hash(s.id)});
  }
  rules_.decide(grid, inputs_, now_ns, decisions_);
  replan_off_leg(fleet, grid, now_ns);
  replan_held(fleet, grid, now_ns);
  for (size_t i = 0; i < decisions_.size(); ++i) {
    if (decisions_[i].waiting_since_ns >= 0)
      longest_wait_seen_s_ =
          std::max(longest_wait_seen_s_, static_cast<double>(now_ns - decisions_[i].waiting_since_ns) * 1e-9);
  }
}

void FleetCoordinator::replan_off_leg(Fleet& fleet, const PlanningGrid& grid, int64_t now_ns) {
  constexpr double kOffLegM = 0.1;
  // The wall check walks the whole straight way: once a second per robot, not every tick.
  constexpr int64_t kCheckNs = 1'000'000'000;
  for (size_t i = 0; i < decisions_.size(); ++i) {
    Slot& s = robots_[i];
    if (decisions_[i].order != TrafficOrder::Go || now_ns - s.leg_checked_ns < kCheckNs ||
        now_ns - s.replanned_ns < kCheckNs || !fleet.owns(s.id))
      continue;
    const GoalTracker* t = fleet.tracker(s.id);
    const auto wp = t != nullptr && t->status() == GoalStatus::Active ? t->current_waypoint() : std::nullopt;
    if (!wp || distance_to_segment(s.position, t->leg_start(), *wp) < kOffLegM) continue;
    s.leg_checked_ns = now_ns;
    if (traffic::keeps_off_walls(grid, s.position, *wp, config_.robot_radius_m)) continue;
    s.replanned_ns = now_ns;
    if (fleet.replan_around(s.id, grid)) ++replans_;
  }
}

void FleetCoordinator::replan_held(Fleet& fleet, const PlanningGrid& grid, int64_t now_ns) {
  const auto after = static_cast<int64_t>(config_.replan_after_s * 1e9);
  // A cell more than the reach: the reduced path's straight legs between cell centres stay clear of
  // the body rule too (a leg that grazes it would be held again at once).
  const double reach = 2.0 * config_.robot_radius_m + config_.clearance_m + grid.resolution();
  const auto cells = static_cast<int32_t>(std::ceil(reach / grid.resolution()));
  for (size_t i = 0; i < decisions_.size(); ++i) {
    const TrafficDecision& d = decisions_[i];
    Slot& s = robots_[i];
    if (d.order != TrafficOrder::Wait || d.waiting_since_ns < 0 || now_ns - d.waiting_since_ns < after ||
        now_ns - s.replanned_ns < after || !fleet.owns(s.id))
      continue;
    s.replanned_ns = now_ns;
    // Every other robot as a disc no robot centre may enter: a way around them, if there is one.
    obstacles_ = grid;
    for (size_t k = 0; k < inputs_.size(); ++k) {
      if (k == i || !robots_[k].seen) continue;
      const Vec2 at = inputs_[k].position;
      const auto centre = grid.cell_at(at);
      if (!centre) continue;
      for (int32_t dy = -cells; dy <= cells; ++dy)
        for (int32_t dx = -cells; dx <= cells; ++dx) {
          const Cell c{centre->x + dx, centre->y + dy};
          if (grid.contains(c) && distance(grid.centre(c), at) < reach)
            obstacles_.set(c, static_cast<uint8_t>(obstacles_.at(c) | kCellObstructed));
        }
    }
    if (fleet.replan_around(s.id, obstacles_)) ++replans_;
  }
}

void FleetCoordinator::dispatch(const Fleet& fleet, std::vector<DueWaypoint>& due) {
  const auto held_command = [](DueWaypoint& out, Vec2 hold) {
    out.waypoint = hold;
    out.remaining.assign(1, hold);
  };
  for (DueWaypoint& d : due) {
    const auto it = slots_.find(d.robot_id);
    if (it == slots_.end() || it->second >= decisions_.size()) continue;
    const TrafficDecision& decision = decisions_[it->second];
    if (decision.order != TrafficOrder::Go) held_command(d, decision.hold);
    robots_[it->second].sent_order = decision.order;
    robots_[it->second].sent_hold = decision.hold;
  }
  for (size_t i = 0; i < decisions_.size(); ++i) {
    Slot& s = robots_[i];
    const TrafficDecision& decision = decisions_[i];
    const bool changed =
        decision.order != s.sent_order ||
        (decision.order != TrafficOrder::Go && distance(decision.hold, s.sent_hold) > kResendMoveM);
    if (!changed || !fleet.owns(s.id)) continue;
    const bool listed =
        std::any_of(due.begin(), due.end(), [&](const DueWaypoint& d) { return d.robot_id == s.id; });
    s.sent_order = decision.order;
    s.sent_hold = decision.hold;
    if (listed) continue;
    if (decision.order != TrafficOrder::Go) {
      due.push_back(DueWaypoint{s.id, decision.hold, {decision.hold}});
      continue;
    }
    // Released: its route's waypoint again (a robot without a route just stays where it stepped to).
    const GoalTracker* t = fleet.tracker(s.id);
    if (t == nullptr || t->status() != GoalStatus::Active) continue;
    if (const auto wp = t->current_waypoint()) {
      const auto rest = t->remaining();
      due.push_back(DueWaypoint{s.id, *wp, std::vector<Vec2>(rest.begin(), rest.end())});
    }
  }
}

size_t FleetCoordinator::held() const {
  return static_cast<size_t>(
      std::count_if(decisions_.begin(), decisions_.end(),
                    [](const TrafficDecision& d) { return d.order != TrafficOrder::Go; }));
}

double FleetCoordinator::longest_wait_s(int64_t now_ns) const {
  double longest = 0.0;
  for (const TrafficDecision& d : decisions_)
    if (d.waiting_since_ns >= 0)
      longest = std::max(longest, static_cast<double>(now_ns - d.waiting_since_ns) * 1e-9);
  return longest;
}

TrafficOrder FleetCoordinator::order(const std::string& robot_id) const {
  const auto it = slots_.find(robot_id);
  if (it == slots_.end() || it->second >= decisions_.size()) return TrafficOrder::Go;
  return decisions_[it->second].order;
}

FleetCoordinator::Held FleetCoordinator::hold_of(const std::string& robot_id) const {
  const auto it = slots_.find(robot_id);
  if (it == slots_.end() || it->second >= decisions_.size()) return {};
  const TrafficDecision& d = decisions_[it->second];
  const auto blocker = static_cast<size_t>(d.blocker);
  return Held{d.order, d.hold,
              d.blocker >= 0 && blocker < robots_.size() ? robots_[blocker].id : std::string{}, d.deadlock,
              d.section};
}

double FleetCoordinator::wait_s(const std::string& robot_id, int64_t now_ns) const {
  const auto it = slots_.find(robot_id);
  if (it == slots_.end() || it->second >= decisions_.size() || decisions_[it->second].waiting_since_ns < 0)
    return 0.0;
  return static_cast<double>(now_ns - decisions_[it->second].waiting_since_ns) * 1e-9;
}

std::string FleetCoordinator::leader() const {
  const auto l = static_cast<size_t>(rules_.leader());
  return rules_.leader() >= 0 && l < robots_.size() ? robots_[l].id : std::string{};
}

}  // namespace slam::planner
