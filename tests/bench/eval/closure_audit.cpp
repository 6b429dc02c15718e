// Loop closures judged against the ground truth (see closure_audit.hpp).
#include "eval/closure_audit.hpp"

#include <algorithm>

namespace slam::bench {

ChangeErrors change_errors(const CorrectionChange& change, const Pose& world_from_map) {
  const Vec2 before = world_from_map.transform(change.before.compose(change.reported_pose).position());
  const Vec2 after = world_from_map.transform(change.after.compose(change.reported_pose).position());
  return {distance(before, change.true_position), distance(after, change.true_position),
          distance(before, after)};
}

ClosureAudit audit_corrections(std::span<const CorrectionChange> changes, const Pose& world_from_map,
                               double false_closure_increase_m) {
  ClosureAudit audit;
  for (const CorrectionChange& change : changes) {
    const ChangeErrors e = change_errors(change, world_from_map);
    ++audit.corrections;
    audit.versions_missed += change.versions_missed;
    audit.largest_jump_m = std::max(audit.largest_jump_m, e.jump_m);
    const double increase = e.after_m - e.before_m;
    if (!change.loop) {
      if (increase > false_closure_increase_m) ++audit.false_matches;
      continue;
    }
    ++audit.loop_corrections;
    audit.largest_loop_jump_m = std::max(audit.largest_loop_jump_m, e.jump_m);
    audit.worst_increase_m = std::max(audit.worst_increase_m.value_or(increase), increase);
    if (increase <= false_closure_increase_m) continue;
    ++audit.false_closures;
    audit.false_closure_list.push_back({change.robot_id, change.version, change.truth_stamp_ns, e});
  }
  return audit;
}

}  // namespace slam::bench
