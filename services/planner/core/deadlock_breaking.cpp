// Pass 4 of the traffic rules (traffic_rules.hpp), wait-for cycles. Waits form a graph (robot ->
// the robot it waits for); a cycle (two robots nose to nose in a corridor) is a deadlock.
// Invariant: every cycle loses an edge this tick when any robot of it, or of the queues behind it,
// has room: a member steps off the way of the robot waiting for it (the same member on every
// planner), or else the robots queued behind the members back off, nearest first. A chain that
// ends at a robot with no route ends in that robot stepping aside.
#include <algorithm>
#include <tuple>

#include "planner/core/traffic_rules.hpp"

namespace slam::planner {

void TrafficRules::resolve_deadlocks(const PlanningGrid& grid, std::span<const TrafficRobot> robots,
                                     std::vector<TrafficDecision>& decisions) {
  const size_t n = robots.size();
  visit_.assign(n, 0);
  waited_by_.resize(n);
  uint32_t walk = 0;
  for (size_t s = 0; s < n; ++s) {
    if (decisions[s].order != TrafficOrder::Wait || visit_[s] != 0) continue;
    ++walk;
    size_t cur = s, prev = s;
    // Follow who waits for whom until the chain ends, meets an earlier walk or closes on itself.
    while (visit_[cur] == 0) {
      visit_[cur] = walk;
      if (decisions[cur].order != TrafficOrder::Wait || decisions[cur].blocker < 0) break;
      prev = cur;
      cur = static_cast<size_t>(decisions[cur].blocker);
    }
    if (visit_[cur] != walk) continue;  // joined a chain already handled
    if (decisions[cur].order == TrafficOrder::Wait && decisions[cur].blocker >= 0 &&
        visit_[static_cast<size_t>(decisions[cur].blocker)] == walk && cur != prev) {
      // A cycle through cur: its lowest-priority member gives way to the robot it waits for; when it
      // has nowhere to go, the next lowest does.
      cycle_.clear();
      size_t k = cur;
      do {
        cycle_.push_back(static_cast<uint32_t>(k));
        k = static_cast<size_t>(decisions[k].blocker);
      } while (k != cur);
      // The one already stepping aside for this cycle carries on (switching roles midway would send
      // them past each other); then a robot waiting before a section: it stands where there is room,
      // and the one inside it cannot clear the section by stepping aside (the section stays its
      // own); otherwise the highest tie number first: a number every planner gives the robot alike,
      // so planners that each drive one robot of the cycle agree on who moves.
      for (const uint32_t m : cycle_) waited_by_[static_cast<size_t>(decisions[m].blocker)] = m;
      std::sort(cycle_.begin(), cycle_.end(), [&](uint32_t a, uint32_t b) {
        return std::tuple(was_deadlocked_[a], decisions[a].section, robots[a].tie, a) >
               std::tuple(was_deadlocked_[b], decisions[b].section, robots[b].tie, b);
      });
      // The same cycle stays until the yielding robot is out of the way: counted once.
      if (std::none_of(cycle_.begin(), cycle_.end(), [&](uint32_t m) { return was_deadlocked_[m] != 0; }))
        ++deadlocks_;
      // A member steps off the way of the robot waiting for it: that breaks the cycle's edge into
      // it (off the way of the one it waits for would not, unless the two wait for each other).
      bool moved = false;
      for (const uint32_t m : cycle_) {
        yield(grid, robots, m, waited_by_[m], decisions);
        decisions[m].deadlock = true;
        moved = decisions[m].order == TrafficOrder::Yield;
        if (moved) break;
      }
      if (!moved) back_off(grid, robots, decisions);
    } else if (robots[cur].ahead.empty() && cur != prev && decisions[cur].order == TrafficOrder::Go) {
      // The chain ends at a stopped robot: it steps off the way of the one waiting for it.
      yield(grid, robots, cur, prev, decisions);
    }
  }
}

void TrafficRules::back_off(const PlanningGrid& grid, std::span<const TrafficRobot> robots,
                            std::vector<TrafficDecision>& decisions) {
  // No member of the cycle has room to step aside: the robots queued behind them fill the way
  // back. The robots queued behind a member step off the way of the robot that member gives way
  // to, the nearest first, then the ones behind them: room opens behind the member from the end of
  // its queue, and the member backs into it on a later tick.
  constexpr size_t kMaxBackOff = 16;  // robots tried per cycle and tick
  back_off_.clear();
  for (const uint32_t m : cycle_) back_off_.emplace_back(m, waited_by_[m]);
  for (size_t at = 0; at < back_off_.size() && at < kMaxBackOff; ++at) {
    const auto [front, away] = back_off_[at];
    for (size_t q = 0; q < robots.size(); ++q) {
      if (q == away || decisions[q].order != TrafficOrder::Wait ||
          decisions[q].blocker != static_cast<int32_t>(front) ||
          std::find(cycle_.begin(), cycle_.end(), static_cast<uint32_t>(q)) != cycle_.end())
        continue;
      yield(grid, robots, q, away, decisions);
      decisions[q].deadlock = true;
      if (decisions[q].order == TrafficOrder::Yield) return;
      back_off_.emplace_back(static_cast<uint32_t>(q), away);
    }
  }
}

}  // namespace slam::planner
